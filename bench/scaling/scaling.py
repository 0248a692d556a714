#!/usr/bin/env python3
"""Scaling figures for docs/scaling.md: time per step, memory, solver iterations and accuracy of
fastcorot's solvers (CG, block-Jacobi PCG, PETSc CG + GAMG on 1 and 2 ranks) on named meshes:
the regular-grid beams 40x10x10 (18,954 tetrahedra), 76x16x16 (101,250) and 160x40x40 (1,451,034),
and an unstructured Gmsh beam of about a million tetrahedra (unstructured_beam.geo; gmsh from
Debian makes it in the work folder, it is not shipped).

Run by hand (minutes to an hour, never in CI), after scripts/build --release:
    bench/scaling/scaling.py                       every mesh
    bench/scaling/scaling.py --meshes 40x10x10 76x16x16 --out figures.json

Accuracy is the relative error of one implicit-Euler step of the beam from rest under gravity
(|x - x_ref| / |x_ref - x_0|, x_ref from PETSc at tolerance 1e-12); for each solver the loosest
tolerance in a ladder that reaches 1e-6 is timed, so that times compare equal accuracy.
"""
import argparse
import json
import os
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
}
# PETSc options per solver variant: GAMG's default smoothed aggregation, and plain aggregation
# (a far cheaper set-up and hierarchy, more iterations).
VARIANTS = {"gamg": ("gamg", []), "gamg-plain": ("gamg", ["-pc_gamg_agg_nsmooths", "0"]), "pcg": ("pcg", []),
            "cg": ("cg", [])}
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
        subprocess.run(["gmsh", "-3", "-setnumber", "h", str(size), str(ROOT / "bench/scaling/unstructured_beam.geo"),
                        "-o", str(path)], check=True, capture_output=True)
    return path


def run(fastcorot, scene, steps, ranks, threads, dump=None, options=()):
    command = [str(fastcorot), "run", str(scene), "--steps", str(steps), "--threads", str(threads), *options]
    if dump:
        command += ["--dump-state", str(dump), "--dump-steps", f"0,{steps}"]
    if ranks > 1:
        command = ["mpirun", "-q", "--oversubscribe", "--allow-run-as-root", "-np", str(ranks), *command]
    at = command.index(str(fastcorot))
    command[at:at] = ["/usr/bin/time", "-f", "max-rss-kib %M"]
    start = time.perf_counter()
    result = subprocess.run(command, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if result.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: {result.stderr}")
    summary = re.search(r"(\d+) steps in ([\d.]+) s.*?linear solves(?:, mean linear-solver iterations ([\d.]+))?",
                        result.stdout)
    rss = [int(k) * 1024 for k in re.findall(r"max-rss-kib (\d+)", result.stderr)]
    return {"seconds_per_step": float(summary.group(2)) / steps, "iterations": float(summary.group(3) or 0),
            "wall_s": wall, "max_rss_bytes_per_rank": rss}


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


def measure(fastcorot, mesh, work, timing_steps, skip_slow):
    figures = {"mesh": mesh, "tetrahedra": tetrahedra(mesh, work)}
    def scene(solver, tolerance):
        path = work / f"{mesh}_{solver}_{tolerance:g}.scn"
        path.write_text(scene_text(mesh, solver, tolerance, work))
        return path
    reference_dump = work / f"{mesh}_reference.json"
    run(fastcorot, scene("gamg", 1e-12), 1, 1, 1, reference_dump)
    rest, reference = step_positions(reference_dump, 1)
    scale = np.abs(reference - rest).max()
    for variant, (solver, options) in VARIANTS.items():
        if variant in skip_slow and figures["tetrahedra"] > 500000:
            continue
        for tolerance in LADDER:
            dump = work / f"{mesh}_{variant}.json"
            one = run(fastcorot, scene(solver, tolerance), 1, 1, 2 if solver != "gamg" else 1, dump, options)
            error = np.abs(step_positions(dump, 1)[1] - reference).max() / scale
            print(f"  {mesh} {variant} tolerance {tolerance:g}: error {error:.2e}, {one['iterations']:.0f} iterations, "
                  f"{one['seconds_per_step']:.3f} s", flush=True)
            if error <= 1e-6:
                figures[variant] = {"tolerance": tolerance, "error": error, "first_step": one}
                break
        if variant not in figures:
            continue
        # Steady stepping: PETSc on 1 and 2 ranks (one thread each), ours on 2 threads.
        tolerance = figures[variant]["tolerance"]
        for ranks in ((1, 2) if solver == "gamg" else (1,)):
            threads = 1 if solver == "gamg" else 2
            timed = run(fastcorot, scene(solver, tolerance), timing_steps, ranks, threads, None, options)
            figures[variant][f"ranks_{ranks}"] = timed
            print(f"  {mesh} {variant} {ranks} rank(s): {timed}", flush=True)
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--meshes", nargs="+", default=["40x10x10", "76x16x16", "160x40x40", "unstructured-h0.11"])
    parser.add_argument("--fastcorot", default=str(ROOT / "build-release/apps/fastcorot/fastcorot"))
    parser.add_argument("--work", default="/tmp/fastcorot-scaling")
    parser.add_argument("--steps", type=int, default=10, help="steps timed per run (a preconditioner rebuild every 10)")
    parser.add_argument("--skip-slow", nargs="*", default=[], help="solvers not run above 500k tetrahedra")
    parser.add_argument("--out", default=None, help="write the figures as JSON here")
    arguments = parser.parse_args()
    work = pathlib.Path(arguments.work)
    work.mkdir(parents=True, exist_ok=True)
    if shutil.which("mpirun") is None:
        sys.exit("scaling.py: mpirun not found (scripts/setup installs Open MPI)")
    results = []
    for mesh in arguments.meshes:
        print(mesh, flush=True)
        results.append(measure(arguments.fastcorot, mesh, work, arguments.steps, arguments.skip_slow))
        if arguments.out:
            pathlib.Path(arguments.out).write_text(json.dumps(results, indent=1))
    print(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
