"""`pip install .` as a soft-robot user installs fastcorot beside STLIB: into a fresh virtual
environment that sees Debian's packages, offline, on Debian's setuptools. Then, with no PYTHONPATH
and from outside the checkout, `import fastcorot, Sofa, SofaRuntime` come from the environment and
its `fastcorot` command runs a Python scene. The module is built in an existing CMake build folder
(FASTCOROT_CMAKE_BUILD_DIR: already built, so this takes seconds); a fresh build folder is the same
path with a configure step first (setup.py). A build folder that is not one is refused, naming it.

usage: pip_install_test.py PYTHON SOURCE_DIR BUILD_DIR WORK_DIR"""

import os
import shutil
import subprocess
import sys
from pathlib import Path

SCENE = '''
def createScene(root):
    root.addObject("DefaultAnimationLoop")
    root.gravity = [0, -9.81, 0]
    beam = root.addChild("beam")
    beam.addObject("EulerImplicitSolver")
    beam.addObject("CGLinearSolver", iterations=50, tolerance=1e-9, threshold=1e-9)
    beam.addObject("RegularGridTopology", name="grid", n=[4, 2, 2], min=[0, 0, 0], max=[1, 0.2, 0.2])
    beam.addObject("MechanicalObject", name="dofs")
    beam.addObject("UniformMass", totalMass=1)
    beam.addObject("TetrahedronFEMForceField", youngModulus=1e4, poissonRatio=0.3)
    beam.addObject("FixedProjectiveConstraint", indices=[0, 4, 8, 12])
'''


def run(command, env, cwd, expect_ok=True):
    done = subprocess.run([str(c) for c in command], env=env, cwd=cwd, capture_output=True, text=True)
    if expect_ok and done.returncode != 0:
        sys.exit(f"FAILED: {' '.join(map(str, command))} (exit {done.returncode})\n{done.stdout}\n{done.stderr}")
    return done


def main():
    python, source, build, work = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3]), Path(sys.argv[4])
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "FASTCOROT_EXECUTABLE")}
    env.update(PIP_NO_CACHE_DIR="1", PIP_DISABLE_PIP_VERSION_CHECK="1")
    venv = work / ".venv"
    run([python, "-m", "venv", "--system-site-packages", venv], env, work)
    pip = [venv / "bin" / "pip", "install", "--no-build-isolation", "--no-index", source]

    # A folder that is not a CMake build is refused, naming it (and nothing is installed).
    refused = run(pip, {**env, "FASTCOROT_CMAKE_BUILD_DIR": str(work / "nowhere")}, work, expect_ok=False)
    if refused.returncode == 0 or "not a configured CMake build folder" not in refused.stdout + refused.stderr:
        sys.exit(f"FAILED: a bad FASTCOROT_CMAKE_BUILD_DIR was not refused:\n{refused.stdout}\n{refused.stderr}")

    run(pip, {**env, "FASTCOROT_CMAKE_BUILD_DIR": str(build)}, work)
    where = run([venv / "bin" / "python", "-c",
                 "import fastcorot, Sofa, SofaRuntime, SofaImGui, Sofa.constants.Key, fastcorot._core as c\n"
                 "for m in (fastcorot, Sofa, SofaRuntime, SofaImGui, c): print(m.__file__)"], env, work).stdout.split()
    if len(where) != 5 or not all(Path(p).resolve().is_relative_to(venv.resolve()) for p in where):
        sys.exit(f"FAILED: the packages do not come from the environment {venv}: {where}")

    command = venv / "bin" / "fastcorot"
    if not command.is_file():
        sys.exit(f"FAILED: no fastcorot command in {venv / 'bin'}")
    (work / "beam.py").write_text(SCENE)
    ran = run([command, "run", "beam.py", "--steps", "3"], {**env, "PATH": f"{venv / 'bin'}:{env.get('PATH', '')}"}, work)
    if "3 steps in" not in ran.stdout + ran.stderr:
        sys.exit(f"FAILED: `fastcorot run beam.py --steps 3` said:\n{ran.stdout}\n{ran.stderr}")
    missing = run([command, "run", "missing.scn"], env, work, expect_ok=False)
    if missing.returncode == 0 or "missing.scn" not in missing.stderr:
        sys.exit(f"FAILED: a missing scene gave exit {missing.returncode}:\n{missing.stderr}")
    print(f"pip install: fastcorot, Sofa, SofaRuntime and the fastcorot command in {venv}")


if __name__ == "__main__":
    main()
