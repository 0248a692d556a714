"""`pip install .`: CMake builds the compiled module (fastcorot._core, the command line inside it)
and copies the pure-Python packages beside it in <build>/python; this copies those packages into
the wheel. The version is the CMake project's.

FASTCOROT_CMAKE_BUILD_DIR names a CMake build folder to build in (it must be configured already, with
the Python module on: scripts/build's build/ is); without it, build-pip/ is configured for a
Release build without tests. FASTCOROT_JOBS sets the parallel jobs (default: the CPUs)."""

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

from setuptools import setup
from setuptools.command.build import build
from setuptools.dist import Distribution

ROOT = Path(__file__).resolve().parent
PACKAGES = ("fastcorot", "Sofa", "SofaRuntime", "SofaImGui")
PIP_BUILD = ROOT / "build-pip"


def cmake_version():
    found = re.search(r"project\(fastcorot VERSION ([0-9.]+)", (ROOT / "CMakeLists.txt").read_text())
    if not found:
        sys.exit("setup.py: no `project(fastcorot VERSION x.y.z` in CMakeLists.txt")
    return found.group(1)


def run(command):
    print("setup.py:", " ".join(str(c) for c in command), flush=True)
    subprocess.run([str(c) for c in command], check=True)


def cmake_build_folder():
    """The configured CMake build folder to build the module in."""
    given = os.environ.get("FASTCOROT_CMAKE_BUILD_DIR")
    if given:
        folder = Path(given).resolve()
        if not (folder / "CMakeCache.txt").is_file():
            sys.exit(f"setup.py: FASTCOROT_CMAKE_BUILD_DIR={given}: not a configured CMake build folder (no CMakeCache.txt)")
        return folder
    if shutil.which("cmake") is None:
        sys.exit("setup.py: cmake is not installed (Debian: scripts/setup installs what fastcorot needs)")
    generator = ["-G", "Ninja"] if shutil.which("ninja") and not (PIP_BUILD / "CMakeCache.txt").exists() else []
    run(["cmake", "-S", ROOT, "-B", PIP_BUILD, *generator, "-DCMAKE_BUILD_TYPE=Release",
         "-DFASTCOROT_BUILD_TESTS=OFF", "-DFASTCOROT_BUILD_BENCH=OFF", "-DFASTCOROT_BUILD_PYTHON=ON",
         f"-DPython_EXECUTABLE={sys.executable}"])
    return PIP_BUILD


class CMakeBuild(build):
    """Builds the module with CMake, then copies the four packages into the wheel's tree."""

    def run(self):
        super().run()
        folder = cmake_build_folder()
        jobs = os.environ.get("FASTCOROT_JOBS", str(os.cpu_count() or 1))
        run(["cmake", "--build", folder, "--target", "fastcorot_python", "-j", jobs])
        for package in PACKAGES:
            source = folder / "python" / package
            if not (source / "__init__.py").is_file():
                sys.exit(f"setup.py: the CMake build has no {source}/__init__.py (is the Python module on in {folder}?)")
            target = Path(self.build_lib) / package
            shutil.rmtree(target, ignore_errors=True)
            shutil.copytree(source, target, ignore=shutil.ignore_patterns("__pycache__", "CMakeFiles", "*.cmake"))


class CompiledDistribution(Distribution):
    """A wheel for this platform and interpreter: the module is compiled."""

    def has_ext_modules(self):
        return True


PIP_BUILD.mkdir(exist_ok=True)  # setuptools' own build and egg-info folders go there, not into build/
setup(
    version=cmake_version(),
    packages=[],
    py_modules=[],
    distclass=CompiledDistribution,
    cmdclass={"build": CMakeBuild},
    options={"build": {"build_base": str(PIP_BUILD / "setuptools")}, "egg_info": {"egg_base": str(PIP_BUILD)}},
)
