"""Scenes built in Python and read from .scn files: a scene built with add_child/add_object steps
exactly as the same scene read from its file, through the module and through `fastcorot run`; data
are read and written by name; simulated positions and velocities are views of the state."""

import json
import os
import threading
import time

import numpy as np
import pytest

import fastcorot
from conftest import REPOSITORY, beam_example, dump_state, run_cli

BEAM_SCN = REPOSITORY / "examples/cantilever_beam_40x10x10.scn"


def python_beam():
    """examples/cantilever_beam_40x10x10.scn, written in Python (numbers as numbers, not text) by
    examples/python/beam.py."""
    return beam_example().build_beam()


def trajectory(root, steps):
    sim = fastcorot.Simulation(root)
    states = {0: root.beam.state.position.copy()}
    for step in range(1, max(steps) + 1):
        sim.step()
        if step in steps:
            states[step] = root.beam.state.position.copy()
    return states


def test_a_python_scene_steps_as_its_scn_file_in_the_module_and_the_program(tmp_path):
    steps = [1, 10, 20]
    built = trajectory(python_beam(), steps)
    loaded = trajectory(fastcorot.load(BEAM_SCN), steps)
    program = dump_state(BEAM_SCN, [0] + steps, tmp_path)
    assert np.abs(built[20] - built[0]).max() > 1e-3  # it moved
    for step in [0] + steps:
        np.testing.assert_array_equal(built[step], loaded[step])
        np.testing.assert_array_equal(built[step], np.array(program[step]["root/beam"]))


def test_explicit_arrays_in_float32_and_float64_step_as_the_same_scene_written_as_text(tmp_path):
    rng = np.random.default_rng(5)
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]], float) + 0.01 * rng.standard_normal((5, 3))
    tets = np.array([[0, 1, 2, 3], [1, 2, 3, 4]])

    def text(values):  # numbers as a scene file writes them, with Python's round-trip repr
        return " ".join(repr(float(v)) for v in np.ravel(values))

    (tmp_path / "two.scn").write_text(f"""<Node name="root" gravity="0 0 -9.81" dt="0.02">
  <Node name="body">
    <EulerImplicitSolver/> <EigenSimplicialLDLT/>
    <MechanicalObject name="dofs" position="{text(points.astype(np.float32))}"/>
    <TetrahedronSetTopologyContainer tetrahedra="{' '.join(map(str, tets.ravel()))}"/>
    <UniformMass totalMass="2"/>
    <FastTetrahedralCorotationalForceField youngModulus="300 500" poissonRatio="0.3" method="polar"/>
    <FixedProjectiveConstraint indices="0 1"/>
  </Node>
</Node>""")
    results = []
    for dtype in (np.float32, np.float64):
        root = fastcorot.Node("root", gravity=[0, 0, -9.81], dt=0.02)
        body = root.add_child("body")
        body.add_object("EulerImplicitSolver")
        body.add_object("EigenSimplicialLDLT")
        body.add_object("MechanicalObject", name="dofs", position=points.astype(np.float32).astype(dtype))
        body.add_object("TetrahedronSetTopologyContainer", tetrahedra=tets.astype(np.int32))
        body.add_object("UniformMass", totalMass=2)
        body.add_object("FastTetrahedralCorotationalForceField", youngModulus=np.array([300, 500]), poissonRatio=0.3,
                        method="polar")
        body.add_object("FixedProjectiveConstraint", indices=[0, 1])
        sim = fastcorot.Simulation(root)
        sim.step(5)
        results.append(body.dofs.position.copy())
    program = dump_state(tmp_path / "two.scn", [5], tmp_path)
    np.testing.assert_array_equal(results[0], program[5]["root/body"])
    np.testing.assert_array_equal(results[1], program[5]["root/body"])


def test_data_are_read_and_written_by_name():
    root = fastcorot.load(BEAM_SCN)
    fem = root.beam.FEM
    assert fem.type == "FastTetrahedralCorotationalForceField" and fem.name == "FEM"
    np.testing.assert_array_equal(fem.youngModulus, [2000])  # text in the file, an array here
    assert fem.method == "large" and fem["poissonRatio"][0] == 0.3
    assert fem.rayleighStiffness == 0.0  # the table's default
    np.testing.assert_array_equal(root.beam.grid.n, [40, 10, 10])
    np.testing.assert_array_equal(root.gravity, [0, -9, 0])
    assert root["beam/clamp"].box.shape == (6,) and root.dt == 0.01
    assert "youngModulus" in dir(fem) and "FastTetrahedralCorotationalForceField" in fem.help_text()
    fem.youngModulus = 500
    fem["poissonRatio"] = 0.1
    np.testing.assert_array_equal(fem.youngModulus, [500])
    # A change of description shows in the next simulation: the softer beam sags more (after 0.1 s
    # the beam is still mostly falling, hence the small margin).
    stiff, soft = trajectory(fastcorot.load(BEAM_SCN), [10])[10], trajectory(root, [10])[10]
    rest = fastcorot.Simulation(fastcorot.load(BEAM_SCN)).objects[0].rest_position
    assert (rest - soft)[:, 1].max() > 1.05 * (rest - stiff)[:, 1].max()


def test_positions_and_velocities_are_views_of_the_state():
    root = python_beam()
    sim = fastcorot.Simulation(root)
    state = root.beam.state
    view = state.position
    assert not view.flags.owndata and view.flags.writeable
    before = view.copy()
    sim.step(3)
    # The view taken before stepping sees the new state (same memory, never reallocated).
    assert np.shares_memory(view, state.position)
    np.testing.assert_array_equal(view, state.position)
    assert np.abs(view - before).max() > 0
    assert not state.rest_position.flags.writeable  # assigned as a whole (test_rest_positions_written_by_a_script_...)
    with pytest.raises(ValueError, match=r"rest_position: expected shape \(4000, 3\)"):
        state.rest_position = before[:10]


def test_writing_the_view_is_setting_the_initial_state():
    # Velocity written into the live view after building = velocity given in the description.
    push = np.zeros((4000, 3))
    push[:, 2] = 0.5
    through_view = python_beam()
    sim_view = fastcorot.Simulation(through_view)
    through_view.beam.state.velocity[:] = push
    described = python_beam()
    described.beam.state.velocity = push
    sim_described = fastcorot.Simulation(described)
    sim_view.step(4)
    sim_described.step(4)
    np.testing.assert_array_equal(through_view.beam.state.position, described.beam.state.position)
    # Assigning copies into the state (the view stays the same memory).
    view = through_view.beam.state.position
    through_view.beam.state.position = np.zeros((4000, 3))
    assert np.all(view == 0)


def test_dt_and_gravity_of_the_root_are_the_simulations():
    root = python_beam()
    sim = fastcorot.Simulation(root)
    root.dt = 0.005
    assert sim.dt == 0.005
    sim.step(4)
    assert sim.time == pytest.approx(0.02)
    sim.gravity = [0, 0, 0]
    np.testing.assert_array_equal(root.gravity, [0, 0, 0])


def test_threads_default_to_every_core_and_give_the_same_bits():
    """No `threads` means one thread per 2,000 points, at most every core (as `fastcorot run`
    without --threads: 2 for the 4,000-point beam on two cores or more); any count steps to the
    same bits."""
    root = python_beam()
    assert fastcorot.Simulation(root).threads == min(max(1, os.cpu_count() or 1), 2)
    states = {}
    for threads in (1, 2, 3):
        root = python_beam()
        sim = fastcorot.Simulation(root, threads=threads)
        sim.step(3)
        states[threads] = root.beam.state.position.copy()
    np.testing.assert_array_equal(states[2], states[1])
    np.testing.assert_array_equal(states[3], states[1])
    with pytest.raises(ValueError, match="threads = 0: must be at least 1"):
        fastcorot.Simulation(python_beam(), threads=0)


def test_the_gil_is_released_while_stepping():
    root = python_beam()
    sim = fastcorot.Simulation(root)
    started = threading.Event()

    def work():
        started.set()
        sim.step(40)

    worker = threading.Thread(target=work)
    worker.start()
    started.wait()
    count = 0
    begin = time.perf_counter()
    while worker.is_alive():
        count += 1
    worker.join()
    elapsed = time.perf_counter() - begin
    # Holding the GIL through step(40) would leave this loop almost no turns while the steps run.
    assert elapsed > 0.05 and count > 1000, (elapsed, count)
    assert sim.steps_done == 40


def test_the_example_measures_the_tip_as_the_program_moves_it(tmp_path):
    example = beam_example()
    times, displacements = example.tip_displacement(example.build_beam(), 10)
    program = dump_state(BEAM_SCN, [0, 10], tmp_path)
    rest, moved = np.array(program[0]["root/beam"]), np.array(program[10]["root/beam"])
    tip = rest[:, 0] == 16  # the free end of the 16-long beam (the .scn's max x)
    assert tip.sum() == 100  # a 10 x 10 face of grid points
    assert displacements[0] == 0 and times[10] == pytest.approx(0.1)
    assert displacements[10] == pytest.approx(np.mean(moved[tip, 1] - rest[tip, 1]), rel=1e-12)
    assert displacements[10] < -1e-3  # it fell
    example.plot(times, displacements, tmp_path / "tip.png")
    assert (tmp_path / "tip.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def small_beam(solver):
    """A 10 × 3 × 3-point beam under its own weight, clamped at x = 0; `solver(node)` adds the
    linear solver."""
    root = fastcorot.Node("root", dt=0.02, gravity=[0, -9.81, 0])
    beam = root.add_child("beam")
    beam.add_object("EulerImplicitSolver", rayleighStiffness=0.1, rayleighMass=0.1)
    solver(beam)
    beam.add_object("RegularGridTopology", name="grid", n=[10, 3, 3], min=[0, 0, 0], max=[9, 1, 1])
    beam.add_object("MechanicalObject", name="state")
    beam.add_object("TetrahedronSetTopologyContainer", name="tets")
    beam.add_object("Hexa2TetraTopologicalMapping", input="@grid", output="@tets", swapping=True)
    beam.add_object("DiagonalMass", massDensity=1)
    beam.add_object("FastTetrahedralCorotationalForceField", youngModulus=1e4, poissonRatio=0.3)
    beam.add_object("BoxROI", name="box", box=[-0.1, -0.1, -0.1, 0.1, 1.1, 1.1])
    beam.add_object("FixedProjectiveConstraint", indices="@box.indices")
    return root


def test_a_block_jacobi_preconditioned_cg_scene_converges_to_the_direct_solution():
    def pcg(node):
        node.add_object("PCGLinearSolver", iterations=300, tolerance=1e-28, preconditioner="@P")
        node.add_object("BlockJacobiPreconditioner", name="P")

    roots = [small_beam(pcg), small_beam(lambda node: node.add_object("EigenSimplicialLDLT"))]
    for root in roots:
        fastcorot.Simulation(root).step(10)
    pcg_positions, direct_positions = (root.beam.state.position for root in roots)
    rest = roots[1].beam.state.rest_position
    moved = np.abs(direct_positions - rest).max()
    assert moved > 1e-2
    np.testing.assert_allclose(pcg_positions, direct_positions, rtol=0, atol=1e-9 * moved)


def test_integer_arrays_assigned_to_the_state_are_converted():
    root = python_beam()
    fastcorot.Simulation(root)
    state = root.beam.state
    view = state.velocity
    state.velocity = np.full((4000, 3), 2, dtype=np.int16)
    assert view.dtype == np.float64 and np.all(view == 2.0)
    with pytest.raises(TypeError, match="dtype complex128"):
        state.velocity = np.zeros((4000, 3), np.complex128)


def test_tetrahedron_fem_von_mises_stress_and_cutting_from_python():
    root = fastcorot.load(str(REPOSITORY / "examples" / "tetrahedron_fem_beams.scn"))
    sim = fastcorot.Simulation(root)
    sim.step(3)
    fem = root.BeamTFEM_LARGE.FEM
    per_node, per_element = fem.vonMisesPerNode, fem.vonMisesPerElement
    assert per_node.shape == (500,) and per_element.shape == (1824,)
    assert per_element.max() > 0 and np.all(np.isfinite(per_node))
    # Each point's value is the mean over its tetrahedra (SOFA's vonMisesPerNode).
    tetrahedra = sim.tetrahedra(1)
    around = np.any(tetrahedra == 0, axis=1)
    assert per_node[0] == pytest.approx(per_element[around].mean(), rel=1e-12)
    # A TetrahedronFEMForceField is cut as the other force field is.
    new_index = fem.remove_tetrahedra([0, 5])
    assert (new_index == -1).sum() == 2 and len(sim.tetrahedra(1)) == 1822
    sim.step(1)
    assert fem.vonMisesPerElement.shape == (1822,) and np.all(np.isfinite(fem.vonMisesPerNode))


def test_objects_sharing_one_solver_are_one_state_viewed_in_parts(tmp_path):
    # SOFA's solver integrates both objects as one system: each MechanicalObject views its range.
    parts = "".join(
        f"""<Node name="{name}"><MechanicalObject name="dofs" position="{s} 0 0 {s + 1} 0 0 {s} 1 0 {s} 0 1"/>
          <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/><UniformMass totalMass="1"/>
          <TetrahedronFEMForceField youngModulus="100"/><FixedProjectiveConstraint indices="0"/></Node>"""
        for name, s in (("a", 0), ("b", 5)))
    scene = tmp_path / "two.scn"
    scene.write_text(f"""<Node name="root"><Node name="group"><EulerImplicitSolver/><EigenSimplicialLDLT/>
        {parts}</Node></Node>""")
    root = fastcorot.load(scene)
    sim = fastcorot.Simulation(root)
    a, b = root.group.a.dofs, root.group.b.dofs
    assert a.position.shape == (4, 3) and b.position.shape == (4, 3)
    whole = sim._core.position(0)
    assert b.position.__array_interface__["data"][0] == whole.__array_interface__["data"][0] + 4 * 3 * 8
    sim.step(10)
    expected = np.array(dump_state(scene, [10], tmp_path)[10]["root/group"])
    assert np.array_equal(np.vstack([a.position, b.position]), expected)
    b.velocity = np.ones((4, 3))
    assert np.array_equal(sim._core.velocity(0)[4:], np.ones((4, 3)))
    assert not np.any(sim._core.velocity(0)[:4] == 1)


def test_states_are_every_mechanical_object_as_the_program_dumps_them(tmp_path):
    # Two objects under one solver, and a state mapped onto one of them (IdentityMapping): the
    # program's dump of a step and Simulation.states() hold the same names, positions and velocities.
    parts = "".join(
        f"""<Node name="{name}"><MechanicalObject name="dofs" position="{s} 0 0 {s + 1} 0 0 {s} 1 0 {s} 0 1"/>
          <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/><UniformMass totalMass="1"/>
          <TetrahedronFEMForceField youngModulus="100"/><FixedProjectiveConstraint indices="0"/>
          <Node name="copy"><MechanicalObject/><IdentityMapping/></Node></Node>"""
        for name, s in (("a", 0), ("b", 5)))
    scene = tmp_path / "two.scn"
    scene.write_text(f"""<Node name="root"><Node name="group"><EulerImplicitSolver/><EigenSimplicialLDLT/>
        {parts}</Node></Node>""")
    sim = fastcorot.Simulation(fastcorot.load(scene))
    sim.step(3)
    states = sim.states()
    assert list(states) == ["root/group/a/dofs", "root/group/b/dofs", "root/group/a/copy/MechanicalObject1",
                            "root/group/b/copy/MechanicalObject1"]
    out = tmp_path / "state.json"
    run_cli("run", scene, "--steps", 3, "--quiet", "--dump-state", out, "--dump-steps", 3)
    dumped = json.loads(out.read_text())["states"]["3"]
    assert list(dumped) == list(states)
    for key, state in states.items():
        assert state["mapped"] == key.endswith("MechanicalObject1")
        assert dumped[key]["node"] == state["node"] and dumped[key]["object"] == state["object"]
        np.testing.assert_array_equal(state["position"], np.array(dumped[key]["position"]))
        np.testing.assert_array_equal(state["velocity"], np.array(dumped[key]["velocity"]))
    np.testing.assert_array_equal(states["root/group/b/copy/MechanicalObject1"]["velocity"],
                                  states["root/group/b/dofs"]["velocity"])
    assert np.abs(states["root/group/b/dofs"]["velocity"]).max() > 0
