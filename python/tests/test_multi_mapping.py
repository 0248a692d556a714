"""SubsetMultiMapping built from Python as STLIB's rigidified objects build it: a beam whose end is
carried by a fixed rigid body and whose rest is free, one TetrahedronFEMForceField on the joined
state (input given as a list of link paths). It moves as the same beam with its end fixed."""

import numpy as np

import Sofa
import Sofa.Core
import Sofa.Simulation

LENGTH = 4  # points along x: LENGTH x 2 x 2


def beam():
    points = [[i, 0.5 * j, 0.5 * k] for i in range(LENGTH) for j in range(2) for k in range(2)]
    tetrahedra = []
    for i in range(LENGTH - 1):
        def corner(bits):
            return (i + (bits & 1)) * 4 + ((bits >> 1) & 1) * 2 + ((bits >> 2) & 1)
        for a, b in ((1, 2), (1, 4), (2, 1), (2, 4), (4, 1), (4, 2)):
            tetrahedra.append([corner(0), corner(a), corner(a | b), corner(7)])
    return points, tetrahedra


def solvers(node):
    node.addObject("EulerImplicitSolver", rayleighStiffness=0.1, rayleighMass=0)
    node.addObject("SparseLDLSolver")


def beam_root():
    root = Sofa.Core.Node("root")
    root.dt = 0.01
    solvers(root)
    return root


def carried_by_rigid(root, points, **frame_mass):
    """A Rigid3 frame under root with a UniformMass of frame_mass, carrying the beam's first four
    points (its child "carried", RigidMapping in local coordinates)."""
    frame = root.addChild("frame")
    frame.addObject("MechanicalObject", name="dofs", template="Rigid3", position=[0.2, 0.1, 0, 0, 0, 0, 1])
    frame.addObject("UniformMass", **frame_mass)
    carried = frame.addChild("carried")
    carried.addObject("MechanicalObject", name="dofs", position=points[:4])
    carried.addObject("RigidMapping", globalToLocalCoords=True)
    return frame, carried


def moved(root, dofs, steps=30):
    """The state's positions at init and after `steps` steps."""
    Sofa.Simulation.init(root)
    start = np.array(dofs.position.value)
    for _ in range(steps):
        Sofa.Simulation.animate(root, root.dt.value)
    return start, np.array(dofs.position.value)


def whole_beam():
    points, tetrahedra = beam()
    root = beam_root()
    root.addObject("MeshTopology", name="mesh", position=points, tetrahedra=tetrahedra)
    root.addObject("MechanicalObject", name="dofs", position=points)
    root.addObject("UniformMass", vertexMass=0.1)
    root.addObject("FixedProjectiveConstraint", indices=[0, 1, 2, 3])
    root.addObject("TetrahedronFEMForceField", youngModulus=2000, poissonRatio=0.3)
    return root, root.dofs


def join(carried, free, points, tetrahedra):
    """The beam's state joined from its first four points (carried) and the rest (free), below free."""
    joined = free.addChild("joined")
    joined.addObject("MeshTopology", position=points, tetrahedra=tetrahedra)
    joined.addObject("MechanicalObject", name="dofs")
    pairs = [[0, i] for i in range(4)] + [[1, i] for i in range(len(points) - 4)]
    joined.addObject("SubsetMultiMapping", input=[carried.dofs.getLinkPath(), free.dofs.getLinkPath()],
                     output=joined.dofs.getLinkPath(), indexPairs=pairs)
    return joined


def rigidified_beam():
    points, tetrahedra = beam()
    root = beam_root()
    frame, carried = carried_by_rigid(root, points, totalMass=1)
    frame.addObject("FixedProjectiveConstraint", indices=[0])
    free = root.addChild("free")
    free.addObject("MechanicalObject", name="dofs", position=points[4:])
    free.addObject("UniformMass", vertexMass=0.1)
    joined = join(carried, free, points, tetrahedra)
    joined.addObject("TetrahedronFEMForceField", youngModulus=2000, poissonRatio=0.3)
    return root, joined.dofs


def test_a_beam_carried_by_a_fixed_rigid_at_one_end_moves_as_the_beam_fixed_there():
    results = []
    for build in (whole_beam, rigidified_beam):
        start, end = moved(*build())
        results.append(end)
        assert np.abs(end - start).max() > 0.01  # it sags
    np.testing.assert_allclose(results[1], results[0], rtol=0, atol=1e-10)


def free_rigidified_beam(mass_on_joined):
    """The rigidified beam with its rigid free (no FixedProjectiveConstraint) and masses of 0.1 on
    every beam point: on the joined state (STLIB's Rigidify keeps the ElasticMaterialObject's
    UniformMass there), or on the input states (the carried points under their RigidMapping)."""
    points, tetrahedra = beam()
    root = beam_root()
    _, carried = carried_by_rigid(root, points, vertexMass=[0.5, 1, [0.01, 0, 0, 0, 0.01, 0, 0, 0, 0.01]])
    free = root.addChild("free")
    free.addObject("MechanicalObject", name="dofs", position=points[4:])
    if not mass_on_joined:
        carried.addObject("UniformMass", vertexMass=0.1)
        free.addObject("UniformMass", vertexMass=0.1)
    joined = join(carried, free, points, tetrahedra)
    if mass_on_joined:
        joined.addObject("UniformMass", vertexMass=0.1)
    joined.addObject("TetrahedronFEMForceField", youngModulus=2000, poissonRatio=0.3)
    # Pin one free point, so that the body swings rather than falls.
    free.addObject("FixedProjectiveConstraint", indices=[len(points) - 5])
    return root, joined.dofs


def test_a_mass_on_the_joined_state_is_the_masses_on_its_inputs():
    results = []
    for mass_on_joined in (False, True):
        start, end = moved(*free_rigidified_beam(mass_on_joined))
        results.append(end)
        assert np.abs(end[:4] - start[:4]).max() > 0.01  # the rigid end moves
    np.testing.assert_allclose(results[1], results[0], rtol=0, atol=1e-10)
