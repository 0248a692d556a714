"""Shared pieces of the Python tests: where the repository and the `fastcorot` program are, and a
way to run the program. CTest sets FASTCOROT_EXECUTABLE and PYTHONPATH; by hand:
    PYTHONPATH=build/python FASTCOROT_EXECUTABLE=build/apps/fastcorot/fastcorot /usr/bin/python3 -m pytest python/tests
"""

import importlib.util
import json
import os
import pathlib
import subprocess

import pytest

REPOSITORY = pathlib.Path(__file__).resolve().parents[2]


def executable():
    path = pathlib.Path(os.environ.get("FASTCOROT_EXECUTABLE", REPOSITORY / "build/apps/fastcorot/fastcorot"))
    if not path.is_file():
        raise RuntimeError(f"the fastcorot program is not at {path}: build it (scripts/build) or set FASTCOROT_EXECUTABLE")
    return path


def run_cli(*arguments, expect_failure=False):
    """Runs the program; returns its completed process (stdout and stderr as text)."""
    completed = subprocess.run([str(executable()), *map(str, arguments)], capture_output=True, text=True, timeout=300)
    if expect_failure:
        assert completed.returncode == 2, f"expected exit status 2, got {completed.returncode}: {completed.stderr}"
    else:
        assert completed.returncode == 0, completed.stderr
    return completed


def cli_error(*arguments):
    """The message the program prints for a failing command, without its "fastcorot: error: " prefix."""
    stderr = run_cli(*arguments, expect_failure=True).stderr.strip()
    prefix = "fastcorot: error: "
    assert stderr.startswith(prefix), stderr
    return stderr[len(prefix):]


def dump_state(scene, steps, tmp_path):
    """Positions after the given steps, from `fastcorot run --dump-state`: {step: {path: (n, 3) list}}."""
    out = tmp_path / "state.json"
    run_cli("run", scene, "--steps", max(steps), "--quiet", "--dump-state", out,
            "--dump-steps", ",".join(map(str, steps)))
    return {int(step): value for step, value in json.loads(out.read_text())["steps"].items()}


def beam_example():
    """examples/python/beam.py as a module (its build_beam() is the cantilever scene in Python)."""
    path = REPOSITORY / "examples/python/beam.py"
    spec = importlib.util.spec_from_file_location("beam_example", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture
def repository():
    return REPOSITORY
