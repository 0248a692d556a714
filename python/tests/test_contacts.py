"""Contacts from Python: fastcorot.Simulation.contacts() and collision_report() on SOFA's soft cube
falling on a floor (tests/data/sofa_reference/cube_on_floor.scn). The count is SOFA's own
(cube_on_floor_trajectory.json); points and normals follow the closed form of a point over the plane
y = -0.3 (the floor's triangle first, the cube's point second, the normal up); the arrays are those
`fastcorot run --dump-state` writes for the same step."""

import json

import numpy as np

import fastcorot
from conftest import REPOSITORY, run_cli

SCENE = REPOSITORY / "tests/data/sofa_reference/cube_on_floor.scn"
FLOOR = -0.3
ALARM_DISTANCE = 0.3


def sofa_count(step):
    trajectory = json.loads((REPOSITORY / "tests/data/sofa_reference/cube_on_floor_trajectory.json").read_text())
    return trajectory["steps"][str(step)]["contacts"]


def test_contacts_of_the_last_step_as_numpy_arrays(tmp_path):
    sim = fastcorot.Simulation(fastcorot.load(SCENE))
    before = sim.contacts()
    assert before["count"] == 0
    assert before["points"].shape == (0, 2, 3)
    assert before["normals"].shape == (0, 3)
    assert sim.collision_report()["contacts"] == 0

    sim.step(29)
    cube = sim.objects[0].position.copy()  # where detection finds the cube's points at step 30's start
    sim.step(1)
    contacts = sim.contacts()
    n = contacts["count"]
    assert n == sofa_count(30) == sim.collision_report()["contacts"]
    points, normals = contacts["points"], contacts["normals"]
    assert points.shape == (n, 2, 3) and normals.shape == (n, 3)
    assert points.dtype == np.float64
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-12)
    np.testing.assert_allclose(normals, np.tile([0.0, 1.0, 0.0], (n, 1)), atol=1e-12)
    # The second points are cube points; the first their feet on the floor.
    for p in points[:, 1]:
        assert np.any(np.all(cube == p, axis=1)), p
    np.testing.assert_allclose(points[:, 0, 1], FLOOR, atol=1e-12)
    np.testing.assert_allclose(points[:, 0, [0, 2]], points[:, 1, [0, 2]], atol=1e-12)
    heights = points[:, 1, 1] - FLOOR
    assert np.all((heights > 0) & (heights < ALARM_DISTANCE))
    report = sim.collision_report()
    assert report["model_pairs"] == 1 and report["element_pairs"] > 0 and report["degenerate_elements"] == 0

    # The program's dump of the same step holds the same numbers.
    out = tmp_path / "state.json"
    run_cli("run", SCENE, "--steps", 30, "--quiet", "--dump-state", out, "--dump-steps", 30)
    dumped = json.loads(out.read_text())["contacts"]["30"]
    assert dumped["count"] == n
    np.testing.assert_array_equal(np.array(dumped["points"]), points)
    np.testing.assert_array_equal(np.array(dumped["normals"]), normals)


def test_a_scene_without_collision_has_no_contacts(repository):
    sim = fastcorot.Simulation(fastcorot.load(repository / "examples/cantilever_beam_40x10x10.scn"))
    sim.step(1)
    assert sim.contacts()["count"] == 0
    assert sim.contacts()["points"].shape == (0, 2, 3)
    assert sim.collision_report() == {"contacts": 0, "model_pairs": 0, "element_pairs": 0, "degenerate_elements": 0,
                                      "detection_seconds": 0.0, "crossed": 0, "deepest_crossing": 0.0}
