"""FreeMotionAnimationLoop scenes from Python, as SofaPython3 scripts write them: the constraint
solver's constraintForces after a step (a point hanging from a fixed point by a bilateral constraint
carries its weight as the impulse m g dt, SOFA's unit), and a controller that moves a
BilateralLagrangianConstraint's rest_vector every step (the tied point follows it to the solver's
tolerance)."""

import numpy as np
import pytest

import Sofa
import Sofa.Core
import Sofa.Simulation

DT = 0.01
MASS = 2.0


def hanging_point(root, tolerance=1e-12):
    """Point `anchor` held by a FixedProjectiveConstraint at the origin, point `bob` (mass MASS) in
    its own solver's node, tied to it by a BilateralLagrangianConstraint."""
    root.dt = DT
    root.gravity = [0, -9.81, 0]
    root.addObject("FreeMotionAnimationLoop")
    root.addObject("BlockGaussSeidelConstraintSolver", name="solver", tolerance=tolerance, maxIterations=100,
                   computeConstraintForces=True)
    anchor = root.addChild("anchor")
    anchor.addObject("EulerImplicitSolver")
    anchor.addObject("SparseLDLSolver")
    anchor.addObject("MechanicalObject", name="dofs", position=[0, 0, 0])
    anchor.addObject("UniformMass", vertexMass=1)
    anchor.addObject("FixedProjectiveConstraint", indices=[0])
    anchor.addObject("LinearSolverConstraintCorrection")
    bob = root.addChild("bob")
    bob.addObject("EulerImplicitSolver", rayleighMass=0.1)
    bob.addObject("SparseLDLSolver")
    bob.addObject("MechanicalObject", name="dofs", position=[0, 0, 0])
    bob.addObject("UniformMass", vertexMass=MASS)
    bob.addObject("LinearSolverConstraintCorrection")
    root.addObject("BilateralLagrangianConstraint", name="tie", object1="@anchor/dofs", object2="@bob/dofs",
                   first_point=[0], second_point=[0])
    return root


def test_the_impulse_holding_a_weight_is_its_weight_times_dt():
    root = hanging_point(Sofa.Core.Node("root"))
    Sofa.Simulation.init(root)
    for _ in range(5):
        Sofa.Simulation.animate(root, DT)
    forces = np.asarray(root.solver.constraintForces.value)
    assert forces.shape == (3,)
    # The row pulls the bob (+I on object2): up, m g dt, whatever the Rayleigh mass damping.
    np.testing.assert_allclose(forces, [0, MASS * 9.81 * DT, 0], atol=1e-10)
    assert root.solver.currentNumConstraints.value == 3
    np.testing.assert_allclose(root.bob.dofs.position.value[0], [0, 0, 0], atol=1e-12)


def test_a_controller_moves_the_rest_vector_every_step():
    def target(step):
        return np.array([[0.02 * step, 0.01 * step * step, 0.0]])

    class Pull(Sofa.Core.Controller):
        def __init__(self, *args, **kwargs):
            Sofa.Core.Controller.__init__(self, *args, **kwargs)
            self.tie = kwargs["tie"]
            self.step = 0

        def onAnimateBeginEvent(self, event):
            self.step += 1
            self.tie.rest_vector.value = target(self.step)

    root = hanging_point(Sofa.Core.Node("root"))
    root.addObject(Pull(name="pull", tie=root.tie))
    Sofa.Simulation.init(root)
    for step in range(1, 31):
        Sofa.Simulation.animate(root, DT)
        np.testing.assert_allclose(root.bob.dofs.position.value[0], target(step)[0], atol=1e-10)
    np.testing.assert_allclose(root.tie.rest_vector.value, target(30))
    # Switched off: the bob moves on freely, implicit Euler with rayleighMass 0.1 under gravity:
    # v' = v + h (g - 0.1 v) / (1 + 0.1 h), x' = x + h v'.
    root.tie.activate.value = False
    x = np.array(root.bob.dofs.position.value[0])
    v = np.array(root.bob.dofs.velocity.value[0])
    Sofa.Simulation.animate(root, DT)
    v_next = v + DT * (np.array([0, -9.81, 0]) - 0.1 * v) / (1 + 0.1 * DT)
    np.testing.assert_allclose(root.bob.dofs.position.value[0], x + DT * v_next, atol=1e-12)
    assert root.solver.currentNumConstraints.value == 0


def test_bad_values_are_refused_naming_the_constraint():
    root = hanging_point(Sofa.Core.Node("root"))
    Sofa.Simulation.init(root)
    with pytest.warns(UserWarning, match="clamped"):
        root.tie.load.value = 2
    assert root.tie.load.value == 1.0
    with pytest.raises(ValueError, match="rest_vector"):
        root.tie.rest_vector.value = [[np.nan, 0, 0]]


def test_a_rigid_pair_constraint_reads_and_takes_six_numbers_per_rest_vector():
    """A Rigid3 BilateralLagrangianConstraint (SOFA's Rigid3 specialisation): rest_vector holds 6
    numbers per pair (offset, rotation); a script moves the hanging body's offset and it follows."""
    root = Sofa.Core.Node("root")
    root.dt = DT
    root.gravity = [0, -9.81, 0]
    root.addObject("FreeMotionAnimationLoop")
    root.addObject("BlockGaussSeidelConstraintSolver", tolerance=1e-14, maxIterations=1000)
    for name, pose, fixed in (("a", [0, 0, 0, 0, 0, 0, 1], True), ("b", [0, -1, 0, 0, 0, 0, 1], False)):
        body = root.addChild(name)
        body.addObject("EulerImplicitSolver", rayleighMass=0, rayleighStiffness=0)
        body.addObject("CGLinearSolver", iterations=100, tolerance=1e-30, threshold=1e-30)
        body.addObject("MechanicalObject", name="frame", template="Rigid3d", position=[pose])
        body.addObject("UniformMass", totalMass=2)
        body.addObject("UncoupledConstraintCorrection")
        if fixed:
            body.addObject("FixedProjectiveConstraint", indices=[0])
    # No template: SOFA deduces Rigid3 from the linked states, and SofaPython3 takes (n, 6) rows.
    root.addObject("BilateralLagrangianConstraint", name="tie", object1="@a/frame", object2="@b/frame",
                   first_point=[0], second_point=[0], rest_vector=[[0, -1, 0, 0, 0, 0]])
    Sofa.Simulation.init(root)
    np.testing.assert_array_equal(np.asarray(root.tie.rest_vector.value).reshape(-1), [0, -1, 0, 0, 0, 0])
    Sofa.Simulation.animate(root, DT)
    root.tie.rest_vector.value = [[0.1, -1, 0, 0, 0, 0]]
    np.testing.assert_array_equal(np.asarray(root.tie.rest_vector.value).reshape(-1), [0.1, -1, 0, 0, 0, 0])
    for _ in range(3):
        Sofa.Simulation.animate(root, DT)
    np.testing.assert_allclose(root.b.frame.position.value[0][:3], [0.1, -1, 0], atol=1e-9)
    with pytest.raises(ValueError, match=r"expected an \(n, 6\) array"):
        root.tie.rest_vector.value = [[0, 1, 0, 0]]
    # activate and load have no effect on the Rigid3 variant (warned) but read back as written.
    with pytest.warns(UserWarning, match="no effect on a Rigid3"):
        root.tie.activate.value = False
    assert root.tie.activate.value is False or root.tie.activate.value == 0


def test_an_inextensible_wire_as_a_script_writes_it():
    # SOFA's inextensible pendulum, from Python: a DistanceMapping's Vec1 state of edge extensions,
    # held at zero by a UniformLagrangianConstraint. SofaPython3 shows a Vec1 state as (n, 1) arrays;
    # the wire swings down while its edges keep their lengths.
    root = Sofa.Core.Node("root")
    root.dt = DT
    root.gravity = [0, -10, 0]
    root.addObject("FreeMotionAnimationLoop", solveVelocityConstraintFirst=True)
    root.addObject("BlockGaussSeidelConstraintSolver", tolerance=1e-12, maxIterations=1000)
    root.addObject("EulerImplicitSolver")
    root.addObject("SparseLDLSolver")
    root.addObject("GenericConstraintCorrection")
    root.addObject("EdgeSetTopologyContainer", name="edges", position=[[0, 0, 0], [0.5, 0, 0], [1, 0, 0], [1.5, 0, 0]],
                   edges=[[0, 1], [1, 2], [2, 3]])
    root.addObject("MechanicalObject", name="particles")
    root.addObject("FixedProjectiveConstraint", indices=[0])
    root.addObject("DiagonalMass", totalMass=0.01)
    lengths = root.addChild("lengths")
    lengths.addObject("MechanicalObject", name="extensions", template="Vec1")
    lengths.addObject("DistanceMapping", topology="@../edges")
    lengths.addObject("UniformLagrangianConstraint", template="Vec1", iterative=False)
    Sofa.Simulation.init(root)
    for _ in range(20):
        Sofa.Simulation.animate(root, DT)
    extensions = np.asarray(root.lengths.extensions.position.value)
    assert extensions.shape == (3, 1)
    x = np.asarray(root.particles.position.value)
    np.testing.assert_allclose(np.linalg.norm(np.diff(x, axis=0), axis=1) - 0.5, extensions[:, 0], atol=1e-14)
    assert np.abs(extensions).max() < 1e-3
    assert x[3, 1] < -0.1


def test_a_controller_moves_a_stoppers_bound():
    # Two particles on a soft spring, the first fixed: a StopperLagrangianConstraint on the edge's
    # extension (a DistanceMapping's Vec1 value) keeps it below `max`, which the script lowers.
    root = Sofa.Core.Node("root")
    root.dt = DT
    root.gravity = [0, -10, 0]
    root.addObject("FreeMotionAnimationLoop")
    root.addObject("BlockGaussSeidelConstraintSolver", tolerance=1e-12, maxIterations=1000)
    root.addObject("EulerImplicitSolver", rayleighMass=0, rayleighStiffness=0)
    root.addObject("SparseLDLSolver")
    root.addObject("GenericConstraintCorrection")
    root.addObject("EdgeSetTopologyContainer", name="edges", position=[[0, 0, 0], [0, -1, 0]], edges=[[0, 1]])
    root.addObject("MechanicalObject", name="particles")
    root.addObject("FixedProjectiveConstraint", indices=[0])
    root.addObject("UniformMass", totalMass=2)
    root.addObject("MeshSpringForceField", linesStiffness=20, linesDamping=0)
    lengths = root.addChild("lengths")
    lengths.addObject("MechanicalObject", name="extensions", template="Vec1")
    lengths.addObject("DistanceMapping", topology="@../edges")
    lengths.addObject("StopperLagrangianConstraint", name="stop", template="Vec1", index=0, min=-1, max=0.2)
    Sofa.Simulation.init(root)
    for _ in range(60):
        Sofa.Simulation.animate(root, DT)
    assert abs(root.lengths.extensions.position.value[0][0] - 0.2) < 1e-3
    root.lengths.stop.max.value = 0.1
    assert root.lengths.stop.max.value == pytest.approx(0.1)
    seen = []
    for _ in range(60):
        Sofa.Simulation.animate(root, DT)
        seen.append(root.lengths.extensions.position.value[0][0])
    # Pulled back to the new bound (it may bounce below it), never beyond it, and against it again.
    assert max(seen) < 0.1 + 1e-3
    assert max(seen[30:]) > 0.1 - 1e-3
    with pytest.raises(ValueError, match="is above max"):
        root.lengths.stop.min.value = 0.5
