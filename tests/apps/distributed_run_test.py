"""Distributed runs (docs/scaling.md) through mpirun: a 2-rank run of the PETSc beam matches the
1-rank run and the sparse direct solve, with the matrix-free and the assembled operator; rank 0 alone writes the frames; checkpoints of a 2-rank run
resume on 2 ranks and on 1; bad input stops every rank with one line and status 2, never a hang.

usage: distributed_run_test.py FASTCOROT SCENE WORKDIR
"""
import json
import os
import pathlib
import shutil
import subprocess
import sys

import numpy as np

FASTCOROT, SCENE, WORK = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
MPIRUN = shutil.which("mpirun")
ENV = dict(os.environ, OMPI_MCA_btl_vader_single_copy_mechanism="none")
failures = []


def run(arguments, ranks=None, timeout=120):
    command = [FASTCOROT, "run", *map(str, arguments)]
    if ranks:
        command = [MPIRUN, "-q", "--oversubscribe", "--allow-run-as-root", "-np", str(ranks), *command]
    try:
        return subprocess.run(command, capture_output=True, text=True, timeout=timeout, env=ENV)
    except subprocess.TimeoutExpired:
        failures.append(f"{' '.join(command)}: no answer in {timeout} s (a hang)")
        return None


def check(condition, message):
    if not condition:
        failures.append(message)


def positions(dump, step):
    steps = json.loads(pathlib.Path(dump).read_text())["steps"][str(step)]
    return np.array(steps["root/beam"])


def trajectory(scene, name, ranks=None, extra=()):
    dump = WORK / f"{name}.json"
    result = run([scene, "--steps", 15, "--dump-state", dump, "--dump-steps", "0,15", "--quiet", *extra], ranks)
    check(result is not None and result.returncode == 0, f"{name}: {result and result.stderr}")
    return positions(dump, 0), positions(dump, 15)


WORK.mkdir(parents=True, exist_ok=True)
direct_scene = WORK / "direct.scn"
direct_scene.write_text(SCENE.read_text().replace(
    '<PETScLinearSolver ksp="cg" pc="gamg" tolerance="1e-10" maxIterations="500"/>', "<EigenSimplicialLDLT/>"))
check("EigenSimplicialLDLT" in direct_scene.read_text(), "the test scene's solver line changed: update this test")

# The same beam with the assembled matrix as the Krylov operator (the matrix-free product is the
# default) and a preconditioner rebuilt every 5 solves.
assembled_scene = WORK / "assembled.scn"
assembled_scene.write_text(SCENE.read_text().replace('maxIterations="500"/>',
                                                     'maxIterations="500" matrixFree="false" rebuildEvery="5"/>'))
check("matrixFree" in assembled_scene.read_text(), "the test scene's solver line changed: update this test")

rest, one = trajectory(SCENE, "one_rank")
checkpoint = WORK / "two_ranks.ckpt"
checkpoint.unlink(missing_ok=True)
_, two = trajectory(SCENE, "two_ranks", ranks=2, extra=("--checkpoint-every", 10, "--checkpoint", checkpoint))
_, direct = trajectory(direct_scene, "direct")
_, assembled = trajectory(assembled_scene, "assembled_two_ranks", ranks=2)
scale = np.abs(one - rest).max()
check(scale > 1e-3, f"the beam hardly moved ({scale})")
# Solver tolerance 1e-10: the same displacements to 1e-8 of their size.
check(np.abs(two - one).max() <= 1e-8 * scale, f"2 ranks vs 1: {np.abs(two - one).max() / scale}")
check(np.abs(one - direct).max() <= 1e-8 * scale, f"PETSc vs direct: {np.abs(one - direct).max() / scale}")
check(np.abs(assembled - one).max() <= 1e-8 * scale, f"assembled on 2 ranks vs 1: {np.abs(assembled - one).max() / scale}")

# Checkpoints: rank 0 writes the gathered state with the fingerprints of the whole scene, so the
# file is that of a one-process run. A resumed run builds GAMG's interpolation from the matrix of
# its first step (the uninterrupted one from step 1's), so it continues to the solver's tolerance.
check(checkpoint.exists(), "2 ranks: no checkpoint written")
for name, ranks in (("resumed_two_ranks", 2), ("resumed_one_rank", None)):
    dump = WORK / f"{name}.json"
    result = run([SCENE, "--steps", 15, "--resume", checkpoint, "--dump-state", dump, "--dump-steps", "15", "--quiet"],
                 ranks)
    check(result is not None and result.returncode == 0, f"{name}: {result and result.stderr}")
    if result is not None and result.returncode == 0:
        resumed = positions(dump, 15)
        check(np.abs(resumed - two).max() <= 1e-8 * scale, f"{name}: {np.abs(resumed - two).max() / scale} from the uninterrupted run")
other = WORK / "other.scn"
other.write_text(SCENE.read_text().replace('youngModulus="', 'youngModulus="2'))
check(other.read_text() != SCENE.read_text(), "the test scene has no youngModulus: update this test")
result = run([other, "--steps", 15, "--resume", checkpoint], ranks=2)
if result is not None:
    errors = [line for line in result.stderr.splitlines() if line.startswith("fastcorot")]
    check(result.returncode == 2 and len(errors) == 1 and "another model" in errors[0],
          f"resumed with another model: status {result.returncode}, {result.stderr!r}")

# Frames: written once, by rank 0, with every point.
out = WORK / "frames"
shutil.rmtree(out, ignore_errors=True)
result = run([SCENE, "--steps", 2, "--vtu", "--out", out], ranks=2)
check(result is not None and result.returncode == 0, f"frames: {result and result.stderr}")
frames = sorted(p.name for p in out.glob("*.vtu"))
check(frames == ["root_beam_0.vtu", "root_beam_1.vtu", "root_beam_2.vtu"], f"frames: {frames}")
check(f'NumberOfPoints="{len(rest)}"' in (out / "root_beam_2.vtu").read_text(errors="replace"), "a frame lacks points")
summary = run([SCENE, "--steps", 2], ranks=2)
check(summary is not None and summary.stdout.count("fastcorot run: 2 steps") == 1 and "2 ranks" in summary.stdout,
      f"summary: {summary and summary.stdout}")

# Bad input: one line, status 2, on every rank.
one_tetrahedron = WORK / "one_tetrahedron.scn"
one_tetrahedron.write_text("""<Node name="root" dt="0.01">
  <Node name="beam">
    <EulerImplicitSolver/>
    <PETScLinearSolver/>
    <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
    <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
    <DiagonalMass totalMass="1"/>
    <FastTetrahedralCorotationalForceField youngModulus="1000" poissonRatio="0.3"/>
  </Node>
</Node>
""")
cases = {
    "unknown -ksp_type": ([SCENE, "--steps", 2, "-ksp_type", "no_such_ksp"], "-ksp_type no_such_ksp"),
    "non-converging": ([SCENE, "--steps", 2, "-pc_type", "none", "-ksp_max_it", 2], "DIVERGED_ITS"),
    "more ranks than tetrahedra": ([one_tetrahedron, "--steps", 2], "only 1 tetrahedra"),
}
for name, (arguments, expected) in cases.items():
    result = run(arguments, ranks=2)
    if result is None:
        continue
    errors = [line for line in result.stderr.splitlines() if line.startswith("fastcorot")]
    check(result.returncode == 2, f"{name}: status {result.returncode}")
    check(len(errors) == 1 and expected in errors[0], f"{name}: {result.stderr!r}")

for failure in failures:
    print("FAIL:", failure)
sys.exit(1 if failures else 0)
