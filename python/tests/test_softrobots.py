"""SoftRobots' components from a SofaPython3 script: a controller pulls a cable step by step,
as SoftRobots' finger examples do from the keyboard, and reads the cable's outputs."""

import numpy as np
import pytest

import Sofa
import Sofa.Simulation


def finger(root, value_type="displacement", value=0.0):
    """A beam 1 long, held at x = 0, with a cable of three points along its top (our own scene)."""
    root.dt = 0.01
    root.gravity = [0, -9.81, 0]
    root.addObject("FreeMotionAnimationLoop")
    root.addObject("GenericConstraintSolver", maxIterations=1000, tolerance=1e-12)
    beam = root.addChild("finger")
    beam.addObject("EulerImplicitSolver", rayleighMass=0.1, rayleighStiffness=0.1)
    beam.addObject("SparseLDLSolver")
    beam.addObject("RegularGridTopology", n=[6, 2, 2], min=[0, 0, 0], max=[1, 0.2, 0.2])
    beam.addObject("MechanicalObject", name="dofs")
    beam.addObject("TetrahedronFEMForceField", youngModulus=5e4, poissonRatio=0.3)
    beam.addObject("UniformMass", totalMass=1)
    beam.addObject("BoxROI", name="box", box=[-0.01, -0.01, -0.01, 0.01, 0.21, 0.21])
    beam.addObject("FixedProjectiveConstraint", indices="@box.indices")
    beam.addObject("LinearSolverConstraintCorrection")
    cable = beam.addChild("cable")
    cable.addObject("MechanicalObject", name="points", position=[[0.1, 0.18, 0.1], [0.5, 0.18, 0.1], [0.95, 0.18, 0.1]])
    actuator = cable.addObject("CableConstraint", name="aCable", indices=[0, 1, 2], pullPoint=[-0.1, 0.18, 0.1],
                               valueType=value_type, value=[value])
    cable.addObject("BarycentricMapping")
    return actuator


class Puller(Sofa.Core.Controller):
    """Adds 0.002 to the cable's command at each step up to 0.02, as SoftRobots' FingerController does per key press."""

    def __init__(self, *args, **kwargs):
        Sofa.Core.Controller.__init__(self, *args, **kwargs)
        self.cable = kwargs["cable"]
        self.name = "FingerController"

    def onAnimateBeginEvent(self, event):
        command = self.cable.value.value[0]
        self.cable.value = [min(command + 0.002, 0.02)]


def test_a_controller_pulls_the_cable_and_reads_its_outputs():
    root = Sofa.Core.Node("root")
    cable = finger(root)
    root.addObject(Puller(cable=cable))
    Sofa.Simulation.init(root)
    initial = cable.cableInitialLength.value
    assert initial == pytest.approx(1.05, abs=1e-12)
    tip = root.finger.dofs.position.value[5].copy()
    for _ in range(400):
        Sofa.Simulation.animate(root, root.dt.value)
    assert list(cable.value.value) == [0.02]
    assert cable.displacement.value == pytest.approx(0.02, abs=1e-7)
    assert cable.cableLength.value == pytest.approx(initial - 0.02, abs=1e-7)
    assert cable.force.value > 0
    assert root.finger.dofs.position.value[5][1] > tip[1] + 1e-3  # the finger bends up
    with pytest.raises(ValueError, match="aCable.*force is an output"):
        cable.force = 3.0
    with pytest.raises(ValueError, match="valueIndex = 2 but value has 1 entries"):
        cable.valueIndex = 2
    assert cable.valueIndex.value == 0
    cable.pullPoint = [-0.2, 0.18, 0.1]
    assert list(cable.pullPoint.value) == [-0.2, 0.18, 0.1]


def test_force_mode_from_a_script_imposes_the_impulse():
    root = Sofa.Core.Node("root")
    cable = finger(root, "force", 0.05)
    Sofa.Simulation.init(root)
    for _ in range(5):
        Sofa.Simulation.animate(root, root.dt.value)
    assert cable.force.value == 0.05
    cable.value = [0.0]
    Sofa.Simulation.animate(root, root.dt.value)
    assert cable.force.value == 0.0


def test_a_cavity_inflated_from_a_script():
    """A closed cube of 12 triangles inside a block held at its base, as a pneumatic actuator."""
    corners = [[0.3, 0.3, 0.3], [0.7, 0.3, 0.3], [0.7, 0.7, 0.3], [0.3, 0.7, 0.3],
               [0.3, 0.3, 0.7], [0.7, 0.3, 0.7], [0.7, 0.7, 0.7], [0.3, 0.7, 0.7]]
    triangles = [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                 [3, 7, 6], [3, 6, 2], [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5]]
    root = Sofa.Core.Node("root")
    root.dt = 0.01
    root.addObject("FreeMotionAnimationLoop")
    root.addObject("GenericConstraintSolver", maxIterations=1000, tolerance=1e-14)
    block = root.addChild("block")
    block.addObject("EulerImplicitSolver", rayleighMass=0.1, rayleighStiffness=0.1)
    block.addObject("SparseLDLSolver")
    block.addObject("RegularGridTopology", n=[5, 5, 5], min=[0, 0, 0], max=[1, 1, 1])
    block.addObject("MechanicalObject")
    block.addObject("TetrahedronFEMForceField", youngModulus=1e3, poissonRatio=0.3)
    block.addObject("UniformMass", totalMass=1)
    block.addObject("BoxROI", name="base", box=[-0.01, -0.01, -0.01, 1.01, 0.01, 1.01])
    block.addObject("FixedProjectiveConstraint", indices="@base.indices")
    block.addObject("LinearSolverConstraintCorrection")
    cavity = block.addChild("cavity")
    cavity.addObject("MeshTopology", name="surface", position=corners, triangles=triangles)
    cavity.addObject("MechanicalObject", position=corners)
    pressure = cavity.addObject("SurfacePressureConstraint", name="pressure", triangles="@surface.triangles",
                                valueType="volumeGrowth", value=0.0)
    cavity.addObject("BarycentricMapping")
    Sofa.Simulation.init(root)
    assert pressure.initialCavityVolume.value == pytest.approx(0.064, abs=1e-15)
    for step in range(300):
        pressure.value = [min(0.0001 * (step + 1), 0.002)]  # inflated gradually, as SoftRobots' controllers do
        Sofa.Simulation.animate(root, root.dt.value)
    assert pressure.volumeGrowth.value == pytest.approx(0.002, abs=1e-9)
    assert pressure.cavityVolume.value == pytest.approx(0.066, abs=1e-9)
    assert pressure.pressure.value > 0
    with pytest.raises(ValueError, match="volumeGrowth is an output"):
        pressure.volumeGrowth = 1.0


def _example(name):
    import importlib.util
    import pathlib

    path = pathlib.Path(__file__).resolve().parents[2] / f"examples/softrobots/{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    return example


def test_the_pneumatic_finger_example_inflates_as_commanded():
    example = _example("pneumatic_finger")
    root = example.createScene(Sofa.Core.Node("root"))
    Sofa.Simulation.init(root)
    pressure = root.finger.cavity.pressure
    tip = root.finger.dofs.position.value[16].copy()
    for _ in range(30):
        Sofa.Simulation.animate(root, root.dt.value)
    # The output is measured where the step began: the growth the previous step was given.
    assert pressure.volumeGrowth.value == pytest.approx(29e-7, abs=2e-8)
    assert pressure.pressure.value > 0
    assert root.finger.dofs.position.value[16][1] < tip[1] - 1e-3  # the top lengthens: the tip goes down


def test_the_pneumatic_gripper_example_lifts_the_ball_it_grips():
    example = _example("pneumatic_gripper")
    root = example.createScene(Sofa.Core.Node("root"))
    Sofa.Simulation.init(root)
    start = root.ball.dofs.position.value[0][1]
    grip = example.INFLATE_STEPS + example.HOLD_STEPS
    for _ in range(grip):
        Sofa.Simulation.animate(root, root.dt.value)
    # Inflated: the fingers curl in and stop on the ball, still on the floor.
    assert root.ball.dofs.position.value[0][1] == pytest.approx(start, abs=1e-4)
    for finger in (root.finger0, root.finger1, root.finger2):
        assert finger.cavity.pressure.pressure.value == pytest.approx(example.PRESSURE * root.dt.value)
    for _ in range(example.LIFT_STEPS + 20):
        Sofa.Simulation.animate(root, root.dt.value)
    # The fingers' bases went up by 40 mm; the ball went with them, held by friction (a few mm of slip).
    lifted = root.ball.dofs.position.value[0][1] - start
    assert 0.03 < lifted < 0.041
