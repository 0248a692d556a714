"""The README's Python quick start runs as printed, and does what its comments say."""

import os
import re

import numpy as np

from conftest import REPOSITORY


def readme_python_block():
    text = (REPOSITORY / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1, "the README should hold one Python example"
    return blocks[0]


def test_the_readme_python_quick_start_runs(monkeypatch, capsys):
    monkeypatch.chdir(REPOSITORY)  # its file names are relative to the checkout, as a reader runs it
    names = {}
    exec(compile(readme_python_block(), "README.md (Python quick start)", "exec"), names)
    assert names["points"].dtype.kind == "i" and names["field"].dtype == np.float64
    force = names["f"]
    assert force.shape == (4, 3) and force.dtype == np.float64
    np.testing.assert_allclose(force.sum(axis=0), 0, atol=1e-9)
    assert force[1, 0] < 0  # the stretched vertex is pulled back
    assert names["K"].shape == (12, 12)
    assert names["sim"].time > 0.99
    printed = capsys.readouterr().out
    assert printed.count("[") >= 3, printed  # the first three points of the state
