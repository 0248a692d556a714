"""Cutting from Python: ForceField.remove_tetrahedra / add_tetrahedra on a standalone field, and
forcefield.remove_tetrahedra on a force field of a running Simulation (the mesh, the force fields
and the mass follow; the free part of a cut beam falls)."""

import numpy as np
import pytest

import fastcorot


def grid(nx, ny, nz):
    """Points and tetrahedra of an nx × ny × nz-point unit grid, each cell split into 6 tetrahedra
    around its main diagonal (a conforming mesh)."""
    points = np.array([[i, j, k] for k in range(nz) for j in range(ny) for i in range(nx)], float)

    def p(i, j, k):
        return i + nx * (j + ny * k)

    tets = []
    for k in range(nz - 1):
        for j in range(ny - 1):
            for i in range(nx - 1):
                c = [p(i, j, k), p(i + 1, j, k), p(i + 1, j + 1, k), p(i, j + 1, k),
                     p(i, j, k + 1), p(i + 1, j, k + 1), p(i + 1, j + 1, k + 1), p(i, j + 1, k + 1)]
                for a, b in [(1, 2), (2, 3), (3, 7), (7, 4), (4, 5), (5, 1)]:
                    tets.append([c[0], c[a], c[b], c[6]])
    return points, np.array(tets)


def test_removing_then_adding_back_restores_the_forces_and_the_index_map_follows_sofa():
    points, tets = grid(6, 3, 3)
    field = fastcorot.ForceField(points, tets, young_modulus=1000, poisson_ratio=0.3)
    rng = np.random.default_rng(2)
    x = points + 0.05 * rng.standard_normal(points.shape)
    before = field.add_force(x)
    stiffness_before = field.stiffness(x).toarray()
    removed = [3, 0, 17]
    new_index = field.remove_tetrahedra(removed)
    assert field.num_tetrahedra == len(tets) - 3
    # Swap-with-last in decreasing order: 17 takes the last, then 3 the next last, then 0.
    n = len(tets)
    assert list(new_index[[0, 3, 17]]) == [-1, -1, -1]
    assert new_index[n - 1] == 17 and new_index[n - 2] == 3 and new_index[n - 3] == 0
    kept = [t for t in range(n) if t not in removed]
    np.testing.assert_array_equal(field.tetrahedra[new_index[kept]], tets[kept])
    assert np.abs(field.add_force(x) - before).max() > 1e-6
    field.add_tetrahedra(tets[removed])
    np.testing.assert_allclose(field.add_force(x), before, rtol=0, atol=1e-12 * np.abs(before).max())
    np.testing.assert_allclose(field.stiffness(x).toarray(), stiffness_before, rtol=0,
                               atol=1e-12 * np.abs(stiffness_before).max())


def test_bad_cuts_raise_and_change_nothing():
    points, tets = grid(3, 2, 2)
    field = fastcorot.ForceField(points, tets)
    with pytest.raises(ValueError, match="out of range"):
        field.remove_tetrahedra([0, len(tets)])
    with pytest.raises(ValueError, match="listed twice"):
        field.remove_tetrahedra([1, 1])
    with pytest.raises(ValueError, match="degenerate"):
        field.add_tetrahedra([[0, 1, 2, 3]])  # points 0, 1, 2 lie on a line
    with pytest.raises(TypeError):
        field.remove_tetrahedra([0.5])
    assert field.num_tetrahedra == len(tets)


def beam_scene():
    root = fastcorot.Node("root", dt=0.01, gravity=[0, -9.81, 0])
    beam = root.add_child("beam")
    beam.add_object("EulerImplicitSolver", rayleighStiffness=0.1)
    beam.add_object("CGLinearSolver", iterations=200, tolerance=1e-12, threshold=1e-30)
    beam.add_object("RegularGridTopology", name="grid", n=[10, 3, 3], min=[0, 0, 0], max=[9, 1, 1])
    beam.add_object("MechanicalObject", name="state")
    beam.add_object("TetrahedronSetTopologyContainer", name="tets")
    beam.add_object("Hexa2TetraTopologicalMapping", input="@grid", output="@tets", swapping=True)
    beam.add_object("DiagonalMass", massDensity=1)
    beam.add_object("FastTetrahedralCorotationalForceField", name="fem", youngModulus=1e5, poissonRatio=0.3)
    beam.add_object("BoxROI", name="box", box=[-0.1, -0.1, -0.1, 0.1, 1.1, 1.1])
    beam.add_object("FixedProjectiveConstraint", indices="@box.indices")
    return root


def test_cutting_a_running_beam_in_two_drops_the_free_half():
    root = beam_scene()
    with pytest.raises(RuntimeError, match="built"):
        root.beam.fem.remove_tetrahedra([0])
    sim = fastcorot.Simulation(root)
    sim.step(5)
    rest = root.beam.state.rest_position
    tets = sim.tetrahedra(0)
    centres = rest[tets].mean(axis=1)
    layer = np.flatnonzero((centres[:, 0] > 4) & (centres[:, 0] < 5))
    assert len(layer) == 24
    new_index = root.beam.fem.remove_tetrahedra(layer)
    assert len(sim.tetrahedra(0)) == len(tets) - 24
    assert (new_index >= 0).sum() == len(tets) - 24
    sim.step(50)
    position = root.beam.state.position
    free = rest[:, 0] >= 5
    assert (position[free, 1] - rest[free, 1]).mean() < -1.0  # fell more than a metre in half a second
    held = rest[:, 0] <= 4
    assert np.abs(position[held] - rest[held]).max() < 0.1  # the fixed half still hangs
    with pytest.raises(TypeError, match="FastTetrahedralCorotationalForceField"):
        root.beam.state.remove_tetrahedra([0])
    with pytest.raises(ValueError, match="out of range"):
        root.beam.fem.remove_tetrahedra([100000])
