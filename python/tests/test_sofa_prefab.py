"""Sofa.Prefab, as STLIB's prefabs use it: parameters with defaults set from keyword arguments,
init() building the content, parent=, data of the node a component takes the value of."""

import numpy as np
import pytest

import Sofa
import Sofa.Simulation

from conftest import REPOSITORY

CYLINDER = str(REPOSITORY / "examples/meshes/cylinder.msh")


class ElasticBody(Sofa.Prefab):
    """Written here after STLIB's ElasticMaterialObject: a volume mesh with mass, elasticity and a solver."""

    prefabParameters = [
        {"name": "volumeMeshFileName", "type": "string", "help": "volume mesh", "default": ""},
        {"name": "translation", "type": "Vec3d", "help": "moves the mesh", "default": [0.0, 0.0, 0.0]},
        {"name": "youngModulus", "type": "double", "help": "E", "default": 18000.0},
        {"name": "poissonRatio", "type": "double", "help": "nu", "default": 0.3},
        {"name": "totalMass", "type": "double", "help": "mass", "default": 1.0},
        {"name": "collisionMesh", "type": "string", "help": "surface for contacts", "default": ""},
    ]
    prefabData = [{"name": "built", "type": "bool", "help": "init ran", "default": False}]

    def __init__(self, *args, **kwargs):
        Sofa.Prefab.__init__(self, *args, **kwargs)

    def init(self):
        if self.volumeMeshFileName.value == "":
            Sofa.msg_error(self, "no volume mesh")
            return
        self.addObject("EulerImplicitSolver", name="integration")
        self.addObject("SparseLDLSolver", name="solver", template="CompressedRowSparseMatrixd")
        self.loader = self.addObject("MeshGmshLoader", name="loader", filename=self.volumeMeshFileName.value,
                                     translation=list(self.translation.value))
        self.addObject("TetrahedronSetTopologyContainer", src=self.loader.getLinkPath(), name="container")
        self.dofs = self.addObject("MechanicalObject", template="Vec3", name="dofs")
        self.addObject("UniformMass", totalMass=self.totalMass, name="mass")  # a prefab datum as a value
        self.addObject("TetrahedronFEMForceField", template="Vec3", method="large", name="forcefield",
                       poissonRatio=self.poissonRatio.value, youngModulus=self.youngModulus.value)
        self.addObject("FixedProjectiveConstraint", indices=[0, 1, 2, 3, 4, 5])
        if self.collisionMesh:
            raise AssertionError("an empty text datum is false")
        self.built = True


def plain_scene(root):
    body = root.addChild("finger")
    body.addObject("EulerImplicitSolver", name="integration")
    body.addObject("SparseLDLSolver", name="solver", template="CompressedRowSparseMatrixd")
    loader = body.addObject("MeshGmshLoader", name="loader", filename=CYLINDER, translation=[1.0, 0.0, 0.0])
    body.addObject("TetrahedronSetTopologyContainer", src=loader.getLinkPath(), name="container")
    body.addObject("MechanicalObject", template="Vec3", name="dofs")
    body.addObject("UniformMass", totalMass=2.0, name="mass")
    body.addObject("TetrahedronFEMForceField", template="Vec3", method="large", name="forcefield",
                   poissonRatio=0.3, youngModulus=5000.0)
    body.addObject("FixedProjectiveConstraint", indices=[0, 1, 2, 3, 4, 5])


def run(root, steps=5):
    root.dt = 0.01
    root.gravity = [0, -9.81, 0]
    Sofa.Simulation.init(root)
    for _ in range(steps):
        Sofa.Simulation.animate(root, root.dt.value)
    return np.array(root.finger.dofs.position.value)


def test_a_prefab_builds_its_content_from_its_parameters_and_steps_as_the_same_nodes_written_out():
    root = Sofa.Core.Node("root")
    finger = ElasticBody(name="finger", parent=root, volumeMeshFileName=CYLINDER, translation=[1, 0, 0],
                         youngModulus=5000, totalMass=2.0, notAParameter=3)
    assert root.finger is finger and root.getChild("finger") is finger and finger.parents == [root]
    assert finger.built.value is True and finger.poissonRatio.value == 0.3 and finger.youngModulus.value == 5000
    assert isinstance(finger.translation.value, np.ndarray) and list(finger.translation.value) == [1, 0, 0]
    assert finger.getData("youngModulus").value == 5000 and finger.findData("notAParameter") is None
    assert finger.dofs is finger.getObject("dofs") and finger.getLinkPath() == "@/finger"
    finger.youngModulus.value = 4000  # a parameter is a datum: it can be written (no rebuild)
    assert finger.youngModulus.value == 4000
    expected = Sofa.Core.Node("root")
    plain_scene(expected)
    moved = run(root)
    assert np.array_equal(moved, run(expected))
    assert np.abs(moved - np.array(root.finger.dofs.rest_position.value)).max() > 1e-6  # it fell


def test_a_prefab_made_apart_is_added_later_and_reports_a_missing_mesh(capsys):
    root = Sofa.Core.Node("root")
    empty = ElasticBody()
    assert empty.getName() == "ElasticBody" and empty.built.value is False and "[ERROR]" in capsys.readouterr().err
    finger = ElasticBody(name="finger", volumeMeshFileName=CYLINDER, translation=[1, 0, 0], youngModulus=5000,
                         totalMass=2.0)
    root.addChild(finger)
    expected = Sofa.Core.Node("root")
    plain_scene(expected)
    assert np.array_equal(run(root), run(expected))
    with pytest.raises(TypeError, match="a dict with a 'name'"):
        type("Broken", (Sofa.Prefab,), {"prefabParameters": ["youngModulus"]})()
