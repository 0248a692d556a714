"""Nodes added and removed while the scene runs, as SofaPython3 scripts do (a controller creating a
body, then calling its node's init()): the scene is built again from the grown tree and the running
state carried over (fastcorot.Simulation.rebuild), so what was running carries on bitwise as if
nothing had been added, and what was added starts from its scene data at the current time."""

import numpy as np
import pytest

import Sofa
import Sofa.Simulation
from fastcorot.scene import SceneWarning
from test_sofa import PYTHON_EXAMPLES, load_script, tetrahedron_scene

G = 9.81


def add_particle(root, name, height):
    node = root.addChild(name)
    node.addObject("EulerImplicitSolver", rayleighMass=0, rayleighStiffness=0)
    node.addObject("CGLinearSolver", iterations=10, tolerance=1e-30, threshold=1e-30)
    state = node.addObject("MechanicalObject", name="point", position=[[5, height, 5]])
    node.addObject("UniformMass", totalMass=1)
    return node, state


def steps(root, n):
    for _ in range(n):
        Sofa.Simulation.animate(root, root.dt.value)


def test_a_node_added_while_running_starts_now_and_the_rest_carries_on_bitwise():
    grown, uninterrupted = Sofa.Core.Node("root"), Sofa.Core.Node("root")
    body = tetrahedron_scene(grown)
    reference = tetrahedron_scene(uninterrupted)
    for root in (grown, uninterrupted):
        root.gravity = [0, -G, 0]
        Sofa.Simulation.init(root)
    steps(grown, 5)
    node, particle = add_particle(grown, "drop", 5.0)
    node.init()
    assert particle.position.value.tolist() == [[5, 5, 5]]  # placed by its scene data, now
    steps(grown, 10)
    steps(uninterrupted, 15)
    assert np.array_equal(body.position.array(), reference.position.array())
    assert np.array_equal(body.velocity.array(), reference.velocity.array())
    assert grown.time.value == pytest.approx(0.15)
    # Implicit Euler from rest under gravity: y = y0 - h² g (1 + 2 + ... + n) after n steps.
    h = 0.01
    assert particle.position.value[0][1] == pytest.approx(5 - h * h * G * 55, abs=1e-12)
    # Without init(): the tree is built again before the next step; a removed node is dropped.
    add_particle(grown, "late", 2.0)
    grown.removeChild("drop")
    steps(grown, 5)
    steps(uninterrupted, 5)
    assert [c.getName() for c in grown.children] == ["body", "late"]
    assert np.array_equal(body.position.array(), reference.position.array())
    assert grown.late.point.position.value[0][1] == pytest.approx(2 - h * h * G * 15, abs=1e-12)
    assert len(Sofa.Simulation.simulation_of(grown).objects) == 2
    # The removed node's state no longer views the simulation (its index now belongs to another).
    assert particle.position.value.tolist() == [[5, 5, 5]]
    # Sofa.Simulation.init on the running scene takes its changes in; nothing restarts.
    add_particle(grown, "third", 3.0)
    Sofa.Simulation.init(grown)
    assert grown.time.value == pytest.approx(0.20)
    assert np.array_equal(body.position.array(), reference.position.array())


def test_a_change_that_would_switch_the_contacts_off_is_refused_and_the_scene_kept():
    root = Sofa.Core.Node("root")
    root.dt = 0.01
    for component in ("CollisionPipeline", "BruteForceBroadPhase", "BVHNarrowPhase"):
        root.addObject(component)
    root.addObject("MinProximityIntersection", alarmDistance=0.2, contactDistance=0.1)
    root.addObject("CollisionResponse", response="PenalityContactForceField")
    node, _ = add_particle(root, "a", 1.0)
    node.addObject("PointCollisionModel")
    floor = root.addChild("floor")
    floor.addObject("MechanicalObject", position=[[4, 0.9, 4], [6, 0.9, 4], [5, 0.9, 6]])
    floor.addObject("MeshTopology", triangles=[0, 2, 1])
    floor.addObject("TriangleCollisionModel", simulated=False, moving=False)
    Sofa.Simulation.init(root)
    steps(root, 2)
    assert Sofa.Simulation.simulation_of(root).collision_report()["contacts"] == 1
    # A rigid body's PointCollisionModel (SOFA wants its points under a RigidMapping): the pipeline
    # would be switched off.
    bad = root.addChild("bad")
    bad.addObject("EulerImplicitSolver")
    bad.addObject("CGLinearSolver")
    bad.addObject("MechanicalObject", template="Rigid3d", position=[[0, 5, 0, 0, 0, 0, 1]])
    bad.addObject("UniformMass", totalMass=1)
    bad.addObject("PointCollisionModel")
    with pytest.raises(ValueError, match="would lose its collision pipeline"):
        bad.init()
    assert root.time.value == pytest.approx(0.02)
    root.removeChild(bad)
    steps(root, 1)
    assert Sofa.Simulation.simulation_of(root).collision_report()["contacts"] == 1


@pytest.mark.skipif(not PYTHON_EXAMPLES.is_dir(), reason="no ../shared/sofa-scenes")
def test_liver_scriptcontroller_drops_a_rigid_sphere_that_the_liver_throws_back(monkeypatch):
    # SofaPython3's example: Ctrl+L makes a Rigid3d sphere (radius 1, its own solver) above the liver's
    # spheres. Its contact point is its surface point and its radius also enters the contact
    # distance (SOFA's RigidContactMapper): the penalty throws it back up, as SOFA does
    # (tests/data/sofa_reference/rigid_spheres_on_spheres.scn; the liver run as a scene file against
    # SOFA: the sphere within 1e-7 of SOFA's path over 400 steps, docs/collision.md).
    monkeypatch.setenv("FASTCOROT_DATA_PATH", str(PYTHON_EXAMPLES / "../../share"))
    script = load_script(PYTHON_EXAMPLES / "liver-scriptcontroller.py", "liver_scriptcontroller")
    root = Sofa.Core.Node("root")
    script.createScene(root)
    Sofa.Simulation.init(root)
    steps(root, 3)
    liver = root.Liver.dofs.position.array().copy()
    root.SphereCreator.onKeypressedEvent({"key": "L"})
    sphere = root.getChild("FallingSphere-0").getMechanicalState()
    heights, contacts = [], []
    for _ in range(90):
        steps(root, 1)
        heights.append(sphere.position.value[0][1])
        contacts.append(Sofa.Simulation.simulation_of(root).collision_report()["contacts"])
    touched = next(i for i, n in enumerate(contacts) if n > 0)
    assert 20 < touched < 60, "falls from y = 10 onto the liver"
    assert max(heights[touched:]) > heights[touched] + 2, "thrown back up"
    assert not np.array_equal(root.Liver.dofs.position.array(), liver)


def test_a_deactivated_node_is_not_simulated_and_freezes_while_running_as_in_sofa():
    root = Sofa.Core.Node("root")
    root.gravity = [0, -G, 0]
    _, moving = add_particle(root, "moving", 5.0)
    off_node, off = add_particle(root, "off", 3.0)
    off_node.activated = False
    kept_node = root.addChild("kept", activated=False)  # SofaPython3's keyword form
    kept_node.addObject("MechanicalObject", name="point", position=[[1, 1, 1]])
    with pytest.warns(SceneWarning, match="data 'activatd' not used.*did you mean 'activated'"):
        root.addChild("typo", activatd=False)
    Sofa.Simulation.init(root)
    assert off_node.activated.value is False and moving.getContext().activated.value is True
    assert len(Sofa.Simulation.simulation_of(root).objects) == 1
    steps(root, 5)
    h = 0.01
    assert moving.position.value[0][1] == pytest.approx(5 - h * h * G * 15, abs=1e-12)
    assert off.position.value.tolist() == [[5, 3, 5]]  # never initialised, never moved
    # Deactivated while running: the state stays where it was and resumes from there when activated
    # again, as SOFA's visitors skip the node and leave its MechanicalObject alone.
    off_node.activated = True
    steps(root, 5)
    root.moving.activated = False
    steps(root, 3)
    assert moving.position.value[0][1] == pytest.approx(5 - h * h * G * 55, abs=1e-12)
    assert off.position.value[0][1] == pytest.approx(3 - h * h * G * 36, abs=1e-12)  # from rest at activation
    root.moving.activated = True
    steps(root, 5)
    # Ten steps in all for `moving`: the three while deactivated did not count.
    assert moving.position.value[0][1] == pytest.approx(5 - h * h * G * 55 - h * h * G * (11 + 12 + 13 + 14 + 15),
                                                        abs=1e-12)
