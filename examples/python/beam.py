"""The cantilever beam of examples/cantilever_beam_40x10x10.scn, built in Python the way a
SofaPython3 script builds it: a 16 x 4 x 4 beam (40 x 10 x 10 grid points, 4000 points, 18954
tetrahedra) clamped at x = 0 and bending under gravity. Runs 200 steps (2 s) and plots the vertical
displacement of the free end over time.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/beam.py [-o beam_tip.png] [--steps 200]

Needs matplotlib (Debian python3-matplotlib) for the plot; it draws without a display (Agg).
"""

import argparse
import pathlib

import numpy as np

import fastcorot


def build_beam():
    """The scene tree of examples/cantilever_beam_40x10x10.scn."""
    root = fastcorot.Node("root", dt=0.01, gravity=[0, -9, 0])
    root.add_object("RequiredPlugin", pluginName="Sofa.Component.SolidMechanics.FEM.Elastic")
    root.add_object("DefaultAnimationLoop")
    beam = root.add_child("beam")
    beam.add_object("EulerImplicitSolver", rayleighStiffness=0.1, rayleighMass=0.1)
    beam.add_object("CGLinearSolver", iterations=20, tolerance=1e-6, threshold=1e-6)
    grid = beam.add_object("RegularGridTopology", name="grid", n=[40, 10, 10], min=[0, 6, -2], max=[16, 10, 2])
    beam.add_object("MechanicalObject", name="state", template="Vec3d")
    tetrahedra = beam.add_object("TetrahedronSetTopologyContainer", name="tetrahedra")
    beam.add_object("Hexa2TetraTopologicalMapping", input=grid, output=tetrahedra, swapping=True)
    beam.add_object("DiagonalMass", totalMass=50)
    beam.add_object("FastTetrahedralCorotationalForceField", name="FEM", youngModulus=2000, poissonRatio=0.3,
                    method="large")
    clamp = beam.add_object("BoxROI", name="clamp", box=[-0.1, 5, -3, 0.1, 11, 3])
    beam.add_object("FixedProjectiveConstraint", indices=clamp.link("indices"))
    return root


def tip_displacement(root, steps):
    """Times (s) and the mean vertical displacement of the free end (the points at x = 16) after
    each step, from step 0."""
    simulation = fastcorot.Simulation(root)
    state = root.beam.state
    position = state.position  # a view of the simulation's state: it follows the steps
    rest = state.rest_position
    tip = rest[:, 0] == rest[:, 0].max()
    times, displacements = [0.0], [0.0]
    for _ in range(steps):
        simulation.step()
        times.append(simulation.time)
        displacements.append(float(np.mean(position[tip, 1] - rest[tip, 1])))
    return np.array(times), np.array(displacements)


def plot(times, displacements, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(7, 3.5), dpi=100)
    axes.plot(times, displacements, color="tab:blue")
    axes.axhline(0, color="gray", linewidth=0.5)
    axes.set_xlabel("time (s)")
    axes.set_ylabel("tip displacement, y")
    axes.set_title("Cantilever beam 40×10×10 under gravity (E = 2000, ν = 0.3, method large)")
    axes.grid(True, alpha=0.3)
    figure.tight_layout()
    figure.savefig(path)
    plt.close(figure)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="beam_tip.png", help="the PNG to write (default beam_tip.png)")
    parser.add_argument("--steps", type=int, default=200, help="time steps of 0.01 s (default 200)")
    arguments = parser.parse_args()
    times, displacements = tip_displacement(build_beam(), arguments.steps)
    output = pathlib.Path(arguments.output)
    output.parent.mkdir(parents=True, exist_ok=True)
    plot(times, displacements, output)
    lowest = int(np.argmin(displacements))
    print(f"tip displacement: lowest {displacements[lowest]:.4f} at t = {times[lowest]:.2f} s, "
          f"{displacements[-1]:.4f} at t = {times[-1]:.2f} s; plot in {output}")


if __name__ == "__main__":
    main()
