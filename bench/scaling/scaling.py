#!/usr/bin/python3
"""Scaling figures for docs/scaling.md: time per step, set-up, memory, solver iterations and
accuracy of fastcorot's solvers (CG, block-Jacobi PCG, PETSc CG + GAMG on 1 and 2 ranks) on named
meshes: the regular-grid beams 40x10x10 (18,954 tetrahedra), 76x16x16 (101,250) and 160x40x40
(1,451,034), and an unstructured Gmsh beam (unstructured-hH: unstructured_beam.geo meshed at
element size H; gmsh from Debian makes it in the work folder, it is not shipped).

Run by hand (minutes to an hour, never in CI), after scripts/build --release:
    bench/scaling/scaling.py                       every mesh
    bench/scaling/scaling.py --meshes 40x10x10 76x16x16 --out figures.json

Accuracy is the relative error of one implicit-Euler step of the beam from rest under gravity
(|x - x_ref| / |x_ref - x_0|, x_ref from PETSc at tolerance 1e-12); for each solver the loosest
tolerance in a ladder that reaches 1e-6 is the one timed, so that times compare equal accuracy.
Times are the run's own step loop (scene loading left out): the first step alone (set-up
included: PETSc's matrix pattern and GAMG's hierarchy), and the steady step, from a run of
1 + --steps steps less the first step. Memory is each process's peak resident size.
"""
import argparse
import json
import pathlib
import re
import shutil
import subprocess
import sys
import time

import numpy as np

ROOT = pathlib.Path(__file__).resolve().parents[2]
GRIDS = {"40x10x10": (40, 10, 10), "76x16x16": (76, 16, 16), "160x40x40": (160, 40, 40)}
SOLVERS = {
    "cg": '<CGLinearSolver iterations="{iterations}" tolerance="{tolerance}" threshold="1e-30"/>',
    "pcg": '<PCGLinearSolver iterations="{iterations}" tolerance="{tolerance_squared}" preconditioner="@jacobi"/>'
           '<BlockJacobiPreconditioner name="jacobi"/>',
    "gamg": '<PETScLinearSolver ksp="cg" pc="gamg" tolerance="{tolerance}" maxIterations="{iterations}"/>',
    "gamg-assembled": '<PETScLinearSolver ksp="cg" pc="gamg" tolerance="{tolerance}" maxIterations="{iterations}" '
                      'matrixFree="false" rebuildEvery="10" rebuildGrowth="0"/>',
}
# Per variant: the scene's solver, PETSc options, and the (ranks, threads per rank) it is timed on.
# Ours run on both cores as threads; PETSc on 1 rank with 1 and 2 threads (the threads serve
# fastcorot's own products and forces, PETSc's work is one thread per rank), and on 2 ranks.
VARIANTS = {
    "cg": ("cg", [], [(1, 2)]),
    "pcg": ("pcg", [], [(1, 2)]),
    "gamg": ("gamg", [], [(1, 1), (1, 2), (2, 1)]),
    "gamg-plain": ("gamg", ["-pc_gamg_agg_nsmooths", "0"], [(1, 2), (2, 1)]),
    "gamg-assembled": ("gamg-assembled", [], [(1, 1), (2, 1)]),
}
LADDER = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8]


def scene_text(mesh, solver, tolerance, work):
    line = SOLVERS[solver].format(iterations=100000, tolerance=tolerance, tolerance_squared=tolerance**2)
    if mesh in GRIDS:
        n = " ".join(map(str, GRIDS[mesh]))
        topology = (f'<RegularGridTopology name="grid" n="{n}" min="0 6 -2" max="16 10 2"/>'
                    '<MechanicalObject name="state"/><TetrahedronSetTopologyContainer name="tetrahedra"/>'
                    '<Hexa2TetraTopologicalMapping input="@grid" output="@tetrahedra" swapping="true"/>')
    else:
        topology = (f'<MeshGmshLoader name="loader" filename="{unstructured_mesh(mesh, work)}"/>'
                    '<TetrahedronSetTopologyContainer name="tetrahedra" src="@loader"/>'
                    '<MechanicalObject name="state"/>')
    return f"""<Node name="root" dt="0.01" gravity="0 -9 0">
  <Node name="beam">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    {line}
    {topology}
    <DiagonalMass totalMass="50"/>
    <FastTetrahedralCorotationalForceField youngModulus="2000" poissonRatio="0.3" method="large"/>
    <BoxROI name="clamp" box="-0.01 5 -3 0.01 11 3"/>
    <FixedProjectiveConstraint indices="@clamp.indices"/>
  </Node>
</Node>
"""


def unstructured_mesh(mesh, work):
    size = float(mesh.split("-h")[1])
    path = work / f"unstructured_h{size}.msh"
    if not path.exists():
        if shutil.which("gmsh") is None:
            sys.exit("scaling.py: the unstructured mesh needs gmsh (apt-get install gmsh)")
        subprocess.run(["gmsh", "-3", "-nt", "2", "-setnumber", "h", str(size),
                        str(ROOT / "bench/scaling/unstructured_beam.geo"), "-o", str(path)], check=True,
                       capture_output=True)
    return path


def run(fastcorot, scene, steps, ranks, threads, dump=None, options=()):
    command = [str(fastcorot), "run", str(scene), "--steps", str(steps), "--threads", str(threads), *options]
    if dump:
        command += ["--dump-state", str(dump), "--dump-steps", f"0,{steps}"]
    command[0:1] = ["/usr/bin/time", "-f", "max-rss-kib %M", str(fastcorot)]
    if ranks > 1:
        command = ["mpirun", "-q", "--oversubscribe", "--allow-run-as-root", "--bind-to", "none", "-np", str(ranks),
                   *command]
    start = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: {result.stderr}")
    summary = re.search(r"(\d+) steps in ([\d.]+) s.*?linear solves(?:, mean linear-solver iterations ([\d.]+))?",
                        result.stdout)
    rss = [int(k) * 1024 for k in re.findall(r"max-rss-kib (\d+)", result.stderr)]
    return {"seconds": float(summary.group(2)), "iterations": float(summary.group(3) or 0), "wall_s": wall,
            "max_rss_bytes_per_rank": rss}


def tetrahedra(mesh, work):
    if mesh in GRIDS:
        nx, ny, nz = GRIDS[mesh]
        return 6 * (nx - 1) * (ny - 1) * (nz - 1)
    # The tetrahedra (element type 4) of the Gmsh 4.1 ASCII file's element blocks.
    lines = unstructured_mesh(mesh, work).read_text().splitlines()
    at = lines.index("$Elements") + 2
    count = 0
    while not lines[at].startswith("$End"):
        _, _, kind, size = map(int, lines[at].split())
        count += size if kind == 4 else 0
        at += size + 1
    return count


def step_positions(dump, steps):
    frames = json.loads(pathlib.Path(dump).read_text())["steps"]
    return np.array(frames["0"]["root/beam"]), np.array(frames[str(steps)]["root/beam"])


def measure(fastcorot, mesh, work, timing_steps, variants, skip_slow):
    figures = {"mesh": mesh, "tetrahedra": tetrahedra(mesh, work)}
    def scene(solver, tolerance):
        path = work / f"{mesh}_{solver}_{tolerance:g}.scn"
        path.write_text(scene_text(mesh, solver, tolerance, work))
        return path
    reference_dump = work / f"{mesh}_reference.json"
    run(fastcorot, scene("gamg", 1e-12), 1, 1, 2, reference_dump)
    rest, reference = step_positions(reference_dump, 1)
    scale = np.abs(reference - rest).max()
    for variant in variants:
        solver, options, layouts = VARIANTS[variant]
        if variant in skip_slow and figures["tetrahedra"] > 500000:
            continue
        for tolerance in LADDER:
            dump = work / f"{mesh}_{variant}.json"
            first = run(fastcorot, scene(solver, tolerance), 1, 1, 2, dump, options)
            error = np.abs(step_positions(dump, 1)[1] - reference).max() / scale
            print(f"  {mesh} {variant} tolerance {tolerance:g}: error {error:.2e}, {first['iterations']:.0f} iterations, "
                  f"first step {first['seconds']:.3f} s", flush=True)
            if error <= 1e-6:
                figures[variant] = {"tolerance": tolerance, "error": error, "first_step": first}
                break
        if variant not in figures:
            continue
        tolerance = figures[variant]["tolerance"]
        # Enough steady steps for a second or more on the small meshes.
        steps = timing_steps * max(1, round(200000 / figures["tetrahedra"]))
        figures[variant]["steady_steps"] = steps
        for ranks, threads in layouts:
            one = run(fastcorot, scene(solver, tolerance), 1, ranks, threads, None, options)
            timed = run(fastcorot, scene(solver, tolerance), 1 + steps, ranks, threads, None, options)
            timed["first_step_s"] = one["seconds"]
            timed["steady_s_per_step"] = (timed["seconds"] - one["seconds"]) / steps
            timed["bytes_per_tetrahedron"] = sum(timed["max_rss_bytes_per_rank"]) / figures["tetrahedra"]
            figures[variant][f"ranks_{ranks}_threads_{threads}"] = timed
            print(f"  {mesh} {variant} {ranks} rank(s) x {threads} thread(s): first step {one['seconds']:.2f} s, "
                  f"steady {timed['steady_s_per_step']:.3f} s/step, {timed['iterations']:.1f} iterations, "
                  f"{timed['bytes_per_tetrahedron']:.0f} bytes/tetrahedron", flush=True)
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--meshes", nargs="+", default=["40x10x10", "76x16x16", "160x40x40", "unstructured-h0.105"])
    parser.add_argument("--variants", nargs="+", default=list(VARIANTS), choices=list(VARIANTS))
    parser.add_argument("--fastcorot", default=str(ROOT / "build-release/apps/fastcorot/fastcorot"))
    parser.add_argument("--work", default="/tmp/fastcorot-scaling")
    parser.add_argument("--steps", type=int, default=10,
                        help="steady steps timed after the first (times 200k / tetrahedra on smaller meshes)")
    parser.add_argument("--skip-slow", nargs="*", default=[], help="variants not run above 500k tetrahedra")
    parser.add_argument("--out", default=None, help="write the figures as JSON here")
    arguments = parser.parse_args()
    work = pathlib.Path(arguments.work)
    work.mkdir(parents=True, exist_ok=True)
    if shutil.which("mpirun") is None:
        sys.exit("scaling.py: mpirun not found (scripts/setup installs Open MPI)")
    results = []
    for mesh in arguments.meshes:
        print(mesh, flush=True)
        results.append(measure(arguments.fastcorot, mesh, work, arguments.steps, arguments.variants,
                               arguments.skip_slow))
        if arguments.out:
            pathlib.Path(arguments.out).write_text(json.dumps(results, indent=1))
    print(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
