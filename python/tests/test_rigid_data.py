"""Rigid3d MechanicalObjects from Python, as SofaPython3 hands them out: position (n, 7) rows
x y z qx qy qz qw and velocity (n, 6) rows v ω, before and after Sofa.Simulation.init, readable as
numpy arrays and writable through writeableArray(); several rigids under one solver joined by a
SpringForceField (SofaPython3's springForceField.py, written out here)."""

import numpy as np
import pytest

import Sofa
import Sofa.Core
import Sofa.Simulation


def two_balls(root):
    root.gravity = [0, -9.81, 0]
    root.dt = 0.01
    root.addObject("EulerImplicitSolver", rayleighStiffness=0.1, rayleighMass=0.1)
    root.addObject("CGLinearSolver", iterations=25, tolerance=1e-8, threshold=1e-8)
    balls = []
    for name, x in (("ball_0", -2), ("ball_1", 2)):
        node = root.addChild(name)
        node.addObject("MechanicalObject", name="dofs", template="Rigid3d", position=(x, 0, 0) + (0, 0, 0, 1))
        node.addObject("UniformMass", name="mass", totalMass=1)
        node.addObject("PlaneForceField", normal="0 1 0", d="-15", stiffness="10000")
        balls.append(node)
    balls[0].addObject("RestShapeSpringsForceField", name="rest_spring", stiffness=1e1, angularStiffness=1e3)
    root.addObject("SpringForceField", object1=balls[0].dofs.getLinkPath(), object2=balls[1].dofs.getLinkPath(),
                   indices1=[0], indices2=[0], length=[4], stiffness=2)
    return balls


def test_rigid_positions_are_rows_of_seven_and_velocities_rows_of_six():
    root = Sofa.Core.Node("root")
    ball = two_balls(root)[0]
    np.testing.assert_array_equal(ball.dofs.position.value, [[-2, 0, 0, 0, 0, 0, 1]])
    Sofa.Simulation.init(root)
    assert ball.dofs.position.value.shape == (1, 7)
    assert ball.dofs.velocity.value.shape == (1, 6)
    np.testing.assert_array_equal(ball.dofs.rest_position.value, [[-2, 0, 0, 0, 0, 0, 1]])
    for _ in range(10):
        Sofa.Simulation.animate(root, root.dt.value)
    # Both fall; the spring (length 4, at rest) and the floor are not reached yet: as free fall.
    y = ball.dofs.position.value[0, 1]
    assert -0.06 < y < -0.04
    assert not ball.dofs.position.array().flags.writeable


def test_written_rows_move_and_turn_the_rigid_and_the_angular_spring_turns_it_back():
    root = Sofa.Core.Node("root")
    ball = two_balls(root)[0]
    Sofa.Simulation.init(root)
    half = np.sqrt(0.5)
    with ball.dofs.position.writeableArray() as rows:
        rows[0, 1] = 5.0
        rows[0, 3:] = [0, 0, half, half]  # turned 90° about z
    np.testing.assert_allclose(ball.dofs.position.value, [[-2, 5, 0, 0, 0, half, half]])
    with ball.dofs.velocity.writeableArray() as rows:
        rows[0, 5] = 1.0
    assert ball.dofs.velocity.value[0, 5] == 1.0
    Sofa.Simulation.animate(root, root.dt.value)
    # RestShapeSprings' angular stiffness 1000 on inertia 1 turns it back towards rest (about -z).
    assert ball.dofs.velocity.value[0, 5] < -5
    assert ball.dofs.position.value[0, 5] < half


def test_a_rigid_row_of_the_wrong_width_is_refused_with_the_object_named():
    root = Sofa.Core.Node("root")
    ball = two_balls(root)[0]
    Sofa.Simulation.init(root)
    with pytest.raises(ValueError, match="dofs.*7 each"):
        ball.dofs.position.value = [[0, 0, 0, 0, 0, 1]]
