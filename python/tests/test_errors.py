"""Errors: the module raises ValueError, TypeError or FileNotFoundError with the messages the
program prints (compared with the program's own output on the same input), and rejects wrong
shapes and dtypes naming the argument."""

import json
import pathlib

import numpy as np
import pytest

import fastcorot
from conftest import REPOSITORY, cli_error

POINTS = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
TETRAHEDRA = [[0, 1, 2, 3]]


def line_of(marker):
    """The line of this file holding `marker` (where an object was made)."""
    lines = pathlib.Path(__file__).read_text().splitlines()
    return 1 + next(i for i, line in enumerate(lines) if marker in line and "line_of" not in line)


@pytest.mark.parametrize("change", [
    {"tetrahedra": [[0, 1, 2, 7]]},
    {"tetrahedra": [[0, 1, 2, 2]]},
    {"poissonRatio": 0.5},
    {"youngModulus": [1, 2]},
    {"method": "svd"},
    {"points": [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]},
])
def test_force_field_errors_are_the_probes(change, tmp_path):
    case = {"points": POINTS.tolist(), "tetrahedra": TETRAHEDRA, "youngModulus": 1000, "poissonRatio": 0.3,
            "method": "qr", **change}
    (tmp_path / "case.json").write_text(json.dumps(case))
    expected = cli_error("probe", tmp_path / "case.json")
    prefix = f"{tmp_path / 'case.json'}: "
    assert expected.startswith(prefix)
    with pytest.raises(ValueError) as raised:
        fastcorot.ForceField(np.array(case["points"], float), case["tetrahedra"], young_modulus=case["youngModulus"],
                             poisson_ratio=case["poissonRatio"], method=case["method"])
    assert str(raised.value) == expected[len(prefix):]


def test_force_field_rejects_wrong_dtypes_and_shapes():
    with pytest.raises(TypeError, match="points: dtype complex128; expected float32 or float64"):
        fastcorot.ForceField(POINTS.astype(np.complex128), TETRAHEDRA)
    with pytest.raises(TypeError, match="points: dtype bool; expected float32 or float64"):
        fastcorot.ForceField(POINTS.astype(bool), TETRAHEDRA)
    with pytest.raises(TypeError, match="tetrahedra: dtype float64; expected an \\(m, 4\\) array of integer"):
        fastcorot.ForceField(POINTS, np.array(TETRAHEDRA, float))
    with pytest.raises(ValueError, match=r"tetrahedra: expected shape \(m, 4\), got \(1, 3\)"):
        fastcorot.ForceField(POINTS, [[0, 1, 2]])
    with pytest.raises(ValueError, match=r"tetrahedra\[0\] has index -1"):
        fastcorot.ForceField(POINTS, [[0, 1, 2, -1]])
    with pytest.raises(TypeError, match="method: expected a string"):
        fastcorot.ForceField(POINTS, TETRAHEDRA, method=2)
    with pytest.raises(TypeError, match="young_modulus: expected a number or a list of numbers, got a str"):
        fastcorot.ForceField(POINTS, TETRAHEDRA, young_modulus="1000")
    field = fastcorot.ForceField(POINTS.astype(np.float32), TETRAHEDRA)
    with pytest.raises(TypeError, match="x: dtype float64; expected float32 .this ForceField computes in float32"):
        field.add_force(POINTS)
    with pytest.raises(ValueError, match=r"x: expected shape \(4, 3\), got \(3, 3\)"):
        field.add_force(POINTS[:3].astype(np.float32))
    with pytest.raises(TypeError, match="dx: expected an \\(n, 3\\) array of numbers, got a list"):
        field.add_dforce([["a", "b", "c"]] * 4)
    bad = POINTS.copy()
    bad[2, 1] = np.nan
    with pytest.raises(ValueError, match=r"x\[2\] has a coordinate that is not finite \(nan\)"):
        fastcorot.ForceField(POINTS, TETRAHEDRA).potential_energy(bad)


SCENES = {
    "unknown_component": '<PolynomialSpringsForceField/>',
    "unknown_attribute": '<UniformMass totalMass="1" weight="3"/>',
    "broken_link": '<FixedProjectiveConstraint indices="@nowhere.indices"/>',
    "bad_number": '<UniformMass totalMass="heavy"/>',
    "bad_method": '<FastTetrahedralCorotationalForceField method="svd"/>',
}


@pytest.mark.parametrize("name", sorted(SCENES))
def test_scene_errors_are_the_programs(name, tmp_path):
    scene = tmp_path / f"{name}.scn"
    scene.write_text(f"""<Node name="root">
  <Node name="body">
    <EulerImplicitSolver/><CGLinearSolver/>
    <MechanicalObject position="0 0 0  1 0 0  0 1 0  0 0 1"/>
    <TetrahedronSetTopologyContainer tetrahedra="0 1 2 3"/>
    {SCENES[name]}
  </Node>
</Node>""")
    # Python checks scenes strictly (an unknown attribute is an error), as `run --strict` does.
    expected = cli_error("run", scene, "--steps", 1, "--quiet", "--strict")
    with pytest.raises(ValueError) as raised:
        fastcorot.Simulation(fastcorot.load(scene))
    assert str(raised.value) == expected


def test_missing_files_are_file_not_found_errors(tmp_path):
    absent = tmp_path / "absent.scn"
    expected = cli_error("run", absent, "--steps", 1)
    with pytest.raises(FileNotFoundError) as raised:
        fastcorot.load(absent)
    assert str(raised.value) == expected
    scene = tmp_path / "mesh.scn"
    scene.write_text("""<Node name="root"><Node name="body">
  <EulerImplicitSolver/><CGLinearSolver/><MeshGmshLoader name="loader" filename="absent.msh"/>
  <TetrahedronSetTopologyContainer src="@loader"/><MechanicalObject/><UniformMass totalMass="1"/>
  <FastTetrahedralCorotationalForceField/></Node></Node>""")
    expected = cli_error("run", scene, "--steps", 1)
    root = fastcorot.load(scene)
    with pytest.raises(FileNotFoundError) as raised:
        fastcorot.Simulation(root)
    assert str(raised.value) == expected


def test_malformed_scene_file_is_a_value_error_as_in_the_program(tmp_path):
    scene = tmp_path / "broken.scn"
    scene.write_text('<Node name="root">\n  <Node name="a">\n</Node>')
    expected = cli_error("run", scene, "--steps", 1)
    with pytest.raises(ValueError) as raised:
        fastcorot.load(scene)
    assert str(raised.value) == expected


def test_python_scene_errors_name_the_python_line():
    root = fastcorot.Node("root")
    body = root.add_child("body")
    with pytest.raises(ValueError) as raised:
        body.add_object("UniformMass", totalMass=1, weight=3)  # marker: weight
    assert str(raised.value).startswith(f"{__file__}:{line_of('marker: weight')}: UniformMass: unknown attribute "
                                        "'weight'; supported: ")
    body.add_object("EulerImplicitSolver")
    body.add_object("CGLinearSolver")
    body.add_object("MechanicalObject", position=POINTS)
    body.add_object("FixedProjectiveConstraint", indices="@nowhere.indices")  # marker: link
    with pytest.raises(ValueError) as raised:
        fastcorot.Simulation(root)
    assert str(raised.value) == (f"{__file__}:{line_of('marker: link')}: FixedProjectiveConstraint: broken link "
                                 "'@nowhere.indices': no component named 'nowhere' in root/body or above")
    with pytest.raises(ValueError, match="unknown component 'PolynomialSpringsForceField'"):
        body.add_object("PolynomialSpringsForceField")


def test_wrong_data_types_and_shapes_are_rejected_naming_the_data():
    body = fastcorot.Node("root").add_child("body")
    with pytest.raises(ValueError, match=r"MechanicalObject 'dofs': position: expected an \(n, 3\) array of numbers, "
                                         r"got shape \(4, 2\)"):
        body.add_object("MechanicalObject", name="dofs", position=np.zeros((4, 2)))
    with pytest.raises(TypeError, match="drawing: expected True or False, got int 2"):
        body.add_object("FastTetrahedralCorotationalForceField", drawing=2)  # 0 and 1 are SOFA's bools
    with pytest.raises(TypeError, match="method: expected a str, got dict"):
        body.add_object("FastTetrahedralCorotationalForceField", method={"qr": 1})
    # A number for a text is written as SOFA reads it (an option's index, valueType=1); a wrong one
    # is then refused where the scene is built, naming it.
    assert body.add_object("FastTetrahedralCorotationalForceField", name="numbered", method=3)._data["method"] == "3"
    with pytest.raises(TypeError, match="tetrahedra: expected integer indices, got dtype float64"):
        body.add_object("TetrahedronSetTopologyContainer", tetrahedra=[[0.0, 1.0, 2.0, 3.0]])
    with pytest.raises(ValueError, match=r"tetrahedra: expected an \(m, 4\) array of indices, got shape \(2, 3\)"):
        body.add_object("TetrahedronSetTopologyContainer", tetrahedra=[[0, 1, 2], [1, 2, 3]])
    with pytest.raises(ValueError, match="n: expected 3 values, got shape"):
        body.add_object("RegularGridTopology", n=[2, 2])
    fem = body.add_object("FastTetrahedralCorotationalForceField")
    with pytest.raises(ValueError, match="unknown attribute 'youngsModulus'"):
        fem.youngsModulus = 3
    with pytest.raises(AttributeError, match="has no data 'youngsModulus'"):
        fem.youngsModulus  # noqa: B018
    with pytest.raises(AttributeError, match="Node 'body' has no data 'dtt'"):
        body.dtt = 0.1
    with pytest.raises(ValueError, match="dt = -1.0: must be a finite number > 0"):
        body.dt = -1


def test_simulation_errors():
    with pytest.raises(TypeError, match="expected a fastcorot.Node"):
        fastcorot.Simulation(str(REPOSITORY / "examples/cantilever_beam_40x10x10.scn"))
    root = fastcorot.load(REPOSITORY / "examples/four_beams.scn")
    sim = fastcorot.Simulation(root)
    with pytest.raises(TypeError, match="step: n must be an integer"):
        sim.step(1.5)
    with pytest.raises(ValueError, match="step: n = -1: must be >= 0"):
        sim.step(-1)
    state = sim.objects[1]
    with pytest.raises(ValueError, match=r"position: expected shape \(\d+, 3\), got \(2, 3\)"):
        state.position = np.zeros((2, 3))
    state.velocity[5, 0] = np.nan
    with pytest.raises(fastcorot.SimulationError, match=f"diverged at step 1.*{sim.paths[1]}") as raised:
        sim.step()
    assert isinstance(raised.value, RuntimeError)
