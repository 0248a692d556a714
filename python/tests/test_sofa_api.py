"""The Sofa compatibility package's calls, one by one: Data, controllers, matrices, the tree, force
fields written in Python, and the bad calls (docs/python.md)."""

import numpy as np
import pytest

import fastcorot
import Sofa
import Sofa.Simulation
from fastcorot.scene import SceneWarning

from test_sofa import tetrahedron_scene


# --- Data ---------------------------------------------------------------------------------------------

def test_data_values_views_and_assignment():
    root = Sofa.Core.Node("root")
    state = tetrahedron_scene(root)
    root.dt = 0.02
    root.gravity = [0, 0, -10]
    assert root.dt.value == 0.02 and list(root.gravity.value) == [0, 0, -10]
    assert root.body.dofs is state and root.body.FEM.youngModulus.value == 100
    root.body.FEM.youngModulus.value = 50
    assert root.body.FEM.youngModulus.value == 50
    assert state.getLinkPath() == "@/body/dofs" and state.position.getLinkPath() == "@/body/dofs.position"
    assert root.body.getPathName() == "/body" and root.getPathName() == "/"
    Sofa.Simulation.init(root)
    simulation = Sofa.Simulation.simulation_of(root)
    core_view = simulation._core.position(0)
    view = state.position.array()
    assert view.__array_interface__["data"][0] == core_view.__array_interface__["data"][0]
    assert not view.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        view[1, 0] = 5
    with state.position.writeableArray() as x:
        assert x.__array_interface__["data"][0] == core_view.__array_interface__["data"][0]
        x[1, 0] = 1.5
    assert core_view[1, 0] == 1.5
    state.velocity.value = np.ones((4, 3))
    assert np.array_equal(simulation._core.velocity(0), np.ones((4, 3)))
    Sofa.Simulation.animate(root, root.dt.value)
    assert root.time.value == pytest.approx(0.02)
    assert view[1, 0] != 1.5  # the view follows the state


def test_bad_calls_raise_clear_python_exceptions():
    root = Sofa.Core.Node("root")
    state = tetrahedron_scene(root)
    with pytest.raises(RuntimeError, match="call Sofa.Simulation.init"):
        Sofa.Simulation.animate(root, 0.01)
    with pytest.raises(AttributeError, match="did you mean 'position'"):
        state.positon
    with pytest.raises(AttributeError, match="did you mean 'body'"):
        root.bodi
    with pytest.warns(SceneWarning, match="unknown attribute 'youngModulous' ignored.*did you mean 'youngModulus'"):
        root.body.addObject("TetrahedronFEMForceField", youngModulous=3)
    with pytest.raises(ValueError, match="unknown component 'TetrahedronFEMForceFeild'.*did you mean"):
        root.body.addObject("TetrahedronFEMForceFeild")
    with pytest.raises(TypeError, match="expected a number"):
        root.body.addObject("UniformMass", totalMass=[1, 2])
    with pytest.raises(TypeError, match="keyword arguments"):
        root.body.addObject("UniformMass", 3)
    with pytest.raises(TypeError, match="component type"):
        root.body.addObject(3)
    with pytest.raises(ValueError, match="dt"):
        root.dt = -1
    with pytest.raises(AttributeError, match="read-only"):
        root.time = 3


def test_controllers_get_the_animation_events_in_scene_order():
    calls = []

    class Recorder(Sofa.Core.Controller):
        def __init__(self, *args, **kwargs):
            Sofa.Core.Controller.__init__(self, *args, **kwargs)

        def init(self):
            calls.append((self.getName(), "init"))

        def onAnimateBeginEvent(self, event):
            calls.append((self.getName(), event["type"], round(self.getContext().getRoot().time.value, 6)))

        def onEvent(self, event):
            calls.append((self.getName(), event["type"], round(self.getContext().getRoot().time.value, 6)))

    root = Sofa.Core.Node("root")
    root.addObject(Recorder(name="first"))
    tetrahedron_scene(root, Recorder(name="second"))
    assert root.first.getName() == "first" and root.body.second.getPathName() == "/body/second"
    Sofa.Simulation.init(root)
    Sofa.Simulation.animate(root, 0.01)
    assert calls == [("first", "init"), ("second", "init"),
                     ("first", "AnimateBeginEvent", 0.0), ("second", "AnimateBeginEvent", 0.0),
                     ("first", "AnimateEndEvent", 0.01), ("second", "AnimateEndEvent", 0.01)]
    Sofa.Simulation.reset(root)
    assert root.time.value == 0.0


def test_a_controller_moving_fixed_points_matches_the_same_motion_through_fastcorots_api():
    def motion(step):
        return np.array([0.01 * step, 0.0, 0.0])

    class Mover(Sofa.Core.Controller):
        def __init__(self, *args, **kwargs):
            Sofa.Core.Controller.__init__(self, *args, **kwargs)
            self.state = kwargs["state"]
            self.step = 0

        def onAnimateBeginEvent(self, event):
            self.step += 1
            with self.state.position.writeableArray() as x:
                x[0] = self.state.rest_position.array()[0] + motion(self.step)

    root = Sofa.Core.Node("root")
    state = tetrahedron_scene(root)
    root.body.addObject(Mover(name="mover", state=state))
    Sofa.Simulation.init(root)
    for _ in range(20):
        Sofa.Simulation.animate(root, root.dt.value)

    plain = fastcorot.Node("root", dt=0.01)
    body = plain.add_child("body")
    body.add_object("EulerImplicitSolver")
    body.add_object("EigenSimplicialLDLT")
    dofs = body.add_object("MechanicalObject", name="dofs", position=[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    body.add_object("TetrahedronSetTopologyContainer", tetrahedra=[0, 1, 2, 3])
    body.add_object("UniformMass", totalMass=2)
    body.add_object("FastTetrahedralCorotationalForceField", youngModulus=100, poissonRatio=0.3)
    body.add_object("FixedProjectiveConstraint", indices=[0])
    simulation = fastcorot.Simulation(plain)
    for step in range(1, 21):
        dofs.position[0] = dofs.rest_position[0] + motion(step)
        simulation.step()
    assert np.array_equal(state.position.array(), dofs.position)
    assert state.position.array()[0, 0] == pytest.approx(0.2)


# --- matrices -----------------------------------------------------------------------------------------

def test_assembled_stiffness_and_mass_matrices():
    pytest.importorskip("scipy")
    root = Sofa.Core.Node("root")
    state = tetrahedron_scene(root)
    Sofa.Simulation.init(root)
    Sofa.Simulation.animate(root, 0.01)
    K = root.body.FEM.assembleKMatrix()
    field = fastcorot.ForceField(state.rest_position.array().copy(), [[0, 1, 2, 3]], young_modulus=100,
                                 poisson_ratio=0.3, method="large")
    # df/dx at the field's last linearisation: the start of the step, the rest shape here.
    expected = field.stiffness(state.rest_position.array().copy()).toarray()
    assert K.shape == (12, 12)
    assert not K.data.flags.owndata and not K.indices.flags.owndata  # the assembled matrix's own arrays
    assert np.allclose(K.toarray(), expected, rtol=1e-12, atol=1e-12)
    M = root.body.mass.assembleMMatrix()
    assert np.array_equal(M.toarray(), np.eye(12) * 0.5)  # UniformMass: totalMass / 4 per point
    other = Sofa.Core.Node("root")
    system = other.addObject("MatrixLinearSystem", name="system")
    with pytest.raises(RuntimeError, match="not initialised"):
        system.get_system_matrix()


# --- the rest of SofaPython3's calls -------------------------------------------------------------------

def test_tree_calls_links_aliases_and_helpers(capsys):
    import SofaRuntime
    from Sofa.Helper import msg_info, msg_warning

    assert SofaRuntime.importPlugin("Sofa.Component.StateContainer")
    root = Sofa.Core.Node("root")
    loose = Sofa.Core.Node("loose")
    assert root.addChild(loose) is loose and root.loose is loose and loose.parents == [root]
    assert root.addChild(loose) is loose and root.children.count(loose) == 1  # the same parent again: nothing changes
    state = tetrahedron_scene(root)
    body = root.getChild("body")
    assert body is root.body and root.getChild("nothing") is None
    assert body.getObject("dofs") is state and body.getObject("nothing") is None
    assert [c.getName() for c in root.children] == ["loose", "body"]
    assert [o.getName() for o in body.objects][:3] == ["EulerImplicitSolver", "EigenSimplicialLDLT", "dofs"]
    assert state.getContext() is body and body.getRoot() is root and body.getLinkPath() == "@/body"
    assert state.getClassName() == "MechanicalObject" and state.getTemplateName() == ""
    assert state.getData("position").getName() == "position" and state.findData("nothing") is None
    assert "position" in [d.getName() for d in state.getDataFields()]
    # A Data (or an object) given as a value is a link to it.
    other = root.addChild("other")
    copy = other.addObject("MechanicalObject", name="copy", position=state.position)
    assert copy.fastcorot_object._data["position"] == "@/body/dofs.position"
    created = other.createObject("UniformMass", totalMass=1)
    assert created.totalMass.value == 1 and created.totalMass.getValueString() == "1.0"
    root.myValue = 3  # a script's own attribute, as SofaPython3 keeps it
    assert root.myValue == 3
    root.bbox = [[-1, -1, -1], [1, 1, 1]]
    assert root.bbox.value == [[-1, -1, -1], [1, 1, 1]]
    msg_info("hello")
    msg_warning(state, "careful")
    err = capsys.readouterr().err
    assert "[INFO]     [PythonScript] hello" in err and "[WARNING]  [dofs] careful" in err


def test_data_sequence_calls_and_writeable_copies():
    root = Sofa.Core.Node("root")
    state = tetrahedron_scene(root)
    indices = root.body.fixed.indices
    assert len(indices) == 1 and indices[0] == 0 and np.array_equal(np.asarray(indices), [0])
    with indices.writeable() as values:  # before init: a copy, written back
        values[0] = 2
    assert root.body.fixed.indices.value.tolist() == [2]
    Sofa.Simulation.init(root)
    state.position[1] = [1.25, 0, 0]  # item assignment writes the state
    assert Sofa.Simulation.simulation_of(root)._core.position(0)[1, 0] == 1.25
    assert state.position == state.position.array()
    with pytest.raises(AttributeError, match="assign the datum's value"):
        state.position.nonsense = 1
    assert "Sofa.Core.Data /body/dofs.position" in repr(state.position)


def test_animate_with_another_dt_reset_and_unload():
    root = Sofa.Core.Node("root")
    state = tetrahedron_scene(root)
    Sofa.Simulation.init(root)
    start = state.position.array().copy()
    Sofa.Simulation.animate(root, 0.05)
    assert root.time.value == pytest.approx(0.05) and root.dt.value == 0.01  # the root's dt stays
    assert not np.array_equal(state.position.array(), start)
    Sofa.Simulation.reset(root)
    assert root.time.value == 0 and np.array_equal(state.position.array(), start)
    Sofa.Simulation.unload(root)
    root.addChild("late")  # the tree can change again; init builds it anew
    with pytest.raises(ValueError, match="dt"):
        Sofa.Simulation.init(root) or Sofa.Simulation.animate(root, -1)


# --- force fields written in Python ----------------------------------------------------------------------

class SpringToRest(Sofa.Core.ForceFieldVec3d):
    """f = -k (x - rest): its forces, its product for CG, its matrix for direct solvers."""

    def __init__(self, *args, **kwargs):
        Sofa.Core.ForceFieldVec3d.__init__(self, *args, **kwargs)
        self.k = kwargs["stiffness"]
        self.rest = np.asarray(kwargs["rest"], dtype=float)
        self.calls = {"addForce": 0, "addDForce": 0, "addKToMatrix": 0}

    def addForce(self, mparams, f, x, v):
        self.calls["addForce"] += 1
        with f.writeableArray() as forces:
            forces[:] += -self.k * (x.value - self.rest)

    def addDForce(self, mparams, df, dx):
        self.calls["addDForce"] += 1
        with df.writeableArray() as dforce:
            dforce[:] += -self.k * mparams["kFactor"] * dx.value

    def addKToMatrix(self, mparams, nNodes, nDofs):
        self.calls["addKToMatrix"] += 1
        return -self.k * mparams["kFactor"] * np.eye(nNodes * nDofs)


@pytest.mark.parametrize("solver", ["EigenSimplicialLDLT", "CGLinearSolver"])
def test_a_python_force_field_steps_as_implicit_euler_says(solver):
    # Points at rest under gravity with mass m each and a spring k to rest: one implicit Euler step
    # gives (m + h^2 k) v1 = h m g, x1 = rest + h v1 (independent of the solver).
    rest = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]
    root = Sofa.Core.Node("root")
    root.dt, root.gravity = 0.1, [0, -10, 0]
    node = root.addChild("points")
    node.addObject("EulerImplicitSolver")
    node.addObject(solver, **({"iterations": 100, "tolerance": 1e-30, "threshold": 1e-30} if solver == "CGLinearSolver" else {}))
    state = node.addObject("MechanicalObject", name="dofs", position=rest)
    node.addObject("UniformMass", totalMass=8)
    spring = node.addObject(SpringToRest(name="spring", stiffness=50.0, rest=rest))
    assert root.points.spring is spring and spring.getPathName() == "/points/spring"
    Sofa.Simulation.init(root)
    Sofa.Simulation.animate(root, root.dt.value)
    m, h, k = 2.0, 0.1, 50.0
    v1 = h * m * -10 / (m + h * h * k)
    expected = np.array(rest, dtype=float) + np.array([0, h * v1, 0])
    assert np.allclose(state.position.array(), expected, rtol=0, atol=1e-12)
    assert spring.calls["addForce"] >= 1
    assert spring.calls["addDForce" if solver == "CGLinearSolver" else "addKToMatrix"] >= 1


def test_a_python_force_field_failing_is_a_simulation_error_naming_it():
    class Broken(Sofa.Core.ForceFieldVec3d):
        def addForce(self, mparams, f, x, v):
            raise ValueError("no forces today")

    root = Sofa.Core.Node("root")
    tetrahedron_scene(root, Broken(name="broken"))
    Sofa.Simulation.init(root)
    with pytest.raises(fastcorot.SimulationError, match="Python ForceField 'broken': addForce: no forces today"):
        Sofa.Simulation.animate(root, 0.01)

    class ReadOnly(Sofa.Core.ForceFieldVec3d):
        def addForce(self, mparams, f, x, v):
            x.value[0, 0] = 1  # positions are read-only in the call

    root = Sofa.Core.Node("root")
    tetrahedron_scene(root, ReadOnly(name="readonly"))
    Sofa.Simulation.init(root)
    with pytest.raises(fastcorot.SimulationError, match="read-only"):
        Sofa.Simulation.animate(root, 0.01)


def test_own_data_of_controllers_and_node_lookups():
    class WithData(Sofa.Core.Controller):
        def __init__(self, *args, **kwargs):
            Sofa.Core.Controller.__init__(self, *args, **kwargs)
            self.addData(name="amplitude", value=0.5, help="how far", type="double")
            self.counter = 0  # an attribute of the script's own

    root = Sofa.Core.Node("root")
    state = tetrahedron_scene(root)
    controller = root.body.addObject(WithData(name="withData"))
    assert controller.amplitude.value == 0.5 and controller.counter == 0
    controller.amplitude = 2.0
    controller.amplitude.value = 3.0
    assert controller.amplitude.value == 3.0 and controller.amplitude.getLinkPath() == "@/body/withData.amplitude"
    with pytest.raises(AttributeError, match="has no attribute 'amplitud'"):
        controller.amplitud
    body = root.body
    assert body.getMechanicalState() is state and body.getMass().getName() == "mass"
    assert body.getForceField(0).getName() == "FEM" and body.getForceField(5) is None
    extra = body.addObject("ConstantForceField", name="push", forces=[[0, 0, 1]], indices=[1])
    body.removeObject(extra)
    body.removeObject(controller)
    assert body.getObject("push") is None and body.getObject("withData") is None
    spare = root.addChild("spare")
    root.removeChild("spare")
    assert root.getChild("spare") is None and spare.parents == []
    with pytest.raises(ValueError, match="no child"):
        root.removeChild("spare")


def test_what_sofapython3_has_and_fastcorot_does_not_is_named():
    import Sofa.Gui

    with pytest.raises(AttributeError, match="Sofa.Core.Topology: SofaPython3 has it"):
        Sofa.Core.Topology
    with pytest.raises(AttributeError, match="Sofa.Simulation.print: SofaPython3 has it"):
        Sofa.Simulation.print
    with pytest.raises(AttributeError, match="Sofa.SofaGL: SofaPython3 has it"):
        Sofa.SofaGL
    with pytest.raises(AttributeError, match="GUIManager.SaveScreenshot: SofaPython3's GUI has it"):
        Sofa.Gui.GUIManager.SaveScreenshot("x.png")


def test_the_remaining_calls_scripts_make(capsys):
    import Sofa.Gui
    import SofaRuntime
    from Sofa.Helper import msg_deprecated, msg_error, msg_fatal

    SofaRuntime.PluginRepository.addFirstPath("/nowhere")
    SofaRuntime.DataRepository.addFirstPath("/nowhere")
    assert Sofa.Gui.GUIManager.ListSupportedGUI(",") == "fastcorot"
    root = Sofa.Core.Node("root")
    child = root.createChild("child")
    state = child.addObject("MechanicalObject", name="dofs", template="Vec3d",
                            position=np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]]))
    assert state.getTemplateName() == "Vec3d" and state.position.toList()[1] == [1.0, 0.0, 0.0]
    assert isinstance(state.position.value, np.ndarray) and not state.position.value.flags.writeable
    Sofa.Simulation.initVisual(root)
    Sofa.Simulation.updateVisual(root)
    msg_error("e")
    msg_deprecated("d")
    msg_fatal("f")
    err = capsys.readouterr().err
    assert "[ERROR]" in err and "[DEPRECATED]" in err and "[FATAL]" in err
    with pytest.raises(TypeError, match="expected a Sofa.Core.Node"):
        Sofa.Simulation.init("root")
    with pytest.raises(TypeError, match="name .str. or a Sofa.Core.Node"):
        root.addChild(3)


def test_calls_stlib_and_softrobots_scripts_make(capsys):
    """What STLIB's prefabs and SoftRobots' controllers call of SofaPython3 (issue 40's first walls)."""
    import Sofa.constants.Key as Key
    from Sofa.constants import KeyCode

    class Named(Sofa.Core.Controller):
        def __init__(self, *args, **kwargs):
            Sofa.Core.Controller.__init__(self, *args, **kwargs)
            self.name = "AnimationManager"  # STLIB's AnimationManagerController does this
            self.listening = True
            self.steps = 0

        def onKeypressedEvent(self, event):
            if event["key"] == Key.uparrow:
                self.steps += 1

    root = Sofa.Core.Node("root", dt=0.02, gravity=[0, -9.81, 0])
    assert root.dt.value == 0.02 and list(root.gravity.value) == [0, -9.81, 0]
    state = tetrahedron_scene(root)
    controller = root.addObject(Named(name="first", printLog=True, unknownOption=3))
    assert controller.getName() == "AnimationManager" and controller.name.value == "AnimationManager"
    assert controller.listening.value is True and controller.printLog.value is True
    assert controller.getData("listening").value is True and controller.findData("unknownOption") is None
    assert [d.getName() for d in controller.getDataFields()][:2] == ["name", "listening"]
    controller.setName("renamed")
    assert root.getObject("renamed", warning=False) is controller and root.hasObject("renamed")
    assert not root.hasObject("AnimationManager")
    assert "renamed" in root.objects and "body" in root.children and "nothing" not in root.objects
    assert root.children["body"] is root.body and root.body.objects["dofs"] is state
    with pytest.raises(KeyError, match="no item named 'nothing'"):
        root.objects["nothing"]
    root._send("KeypressedEvent", key=Key.uparrow)
    assert controller.steps == 1
    assert (Key.uparrow, Key.A, Key.KP_0, Key.space) == (chr(19), "A", "0", " ")
    assert (KeyCode.uparrow, KeyCode.A) == (19, 65)
    # A text datum is false when empty and has a length (STLIB: `if self.collisionMesh:`).
    controller.addData(name="surfaceMesh", value="", type="string")
    controller.addData(name="volumeMesh", value="finger.vtk", type="string")
    assert not controller.surfaceMesh and len(controller.surfaceMesh) == 0
    assert isinstance(controller.surfaceMesh, Sofa.Core.DataString) and isinstance(state.position, Sofa.Core.DataContainer)
    assert controller.volumeMesh and len(controller.volumeMesh) == 10 and state.position and len(state.position) == 4
    Sofa.msg_warning(controller, "hello")
    err = capsys.readouterr().err
    assert "[WARNING]" in err and "[renamed] hello" in err and "test_sofa_api.py" in err


def test_data_repositories_from_scripts(tmp_path):
    import shutil

    import SofaRuntime

    from conftest import REPOSITORY

    folder = tmp_path / "meshes"
    folder.mkdir()
    shutil.copy(REPOSITORY / "examples/meshes/cylinder.msh", folder / "cylinder_from_repository.msh")
    assert SofaRuntime.DataRepository.getFile("cylinder_from_repository.msh") == "cylinder_from_repository.msh"
    SofaRuntime.DataRepository.addFirstPath(str(folder))
    assert SofaRuntime.DataRepository.getFile("cylinder_from_repository.msh") == str(folder / "cylinder_from_repository.msh")
    root = Sofa.Core.Node("root")
    body = root.addChild("body")
    body.addObject("EulerImplicitSolver")
    body.addObject("CGLinearSolver", iterations=10)
    loader = body.addObject("MeshGmshLoader", name="loader", filename="cylinder_from_repository.msh")
    body.addObject("TetrahedronSetTopologyContainer", src=loader.getLinkPath())
    body.addObject("MechanicalObject", name="dofs")
    body.addObject("UniformMass", totalMass=1)
    Sofa.Simulation.init(root)
    assert len(body.dofs.position.value) > 4


def test_what_stlib_and_softrobots_scenes_write():
    """Calls taken from STLIB's prefabs and SoftRobots' tutorials, each once a wall."""
    from conftest import REPOSITORY

    root = Sofa.Core.Node("root")
    root.addObject("VisualStyle")  # unnamed: found by its type's name, as SOFA names it
    root.VisualStyle.displayFlags = "showBehavior"
    assert root.getObject("VisualStyle") is not None
    body = root.addChild("body")
    body.addObject("EulerImplicitSolver")
    body.addObject("CGLinearSolver", iterations=25.0, tolerance=1e-5, threshold=1e-5)  # 25.0 for an integer
    loader = body.addObject("MeshGmshLoader", name="loader", filename=str(REPOSITORY / "examples/meshes/cylinder.msh"))
    # A loader's outputs, given as links before the scene is built (STLIB's ElasticMaterialObject).
    body.addObject("TetrahedronSetTopologyContainer", position=loader.position.getLinkPath(), tetras=loader.tetras.linkpath)
    # Read before init, as SofaPython3 gives them once the objects are added (STLIB's Rigidify reads
    # the container's positions to place its frames): the loader's output, and the container's
    # position through its link.
    points = loader.position.value
    assert points.shape[1] == 3 and len(points) > 4
    np.testing.assert_array_equal(body.TetrahedronSetTopologyContainer.position.value, points)
    assert body.TetrahedronSetTopologyContainer.tetras.value.shape[1] == 4
    body.addObject("MechanicalObject", name="dofs")
    body.addObject("UniformMass", totalMass=1)
    roi = body.addObject("BoxROI", name="roi", box=[-1, -1, -1, 1, 1, 0.1])
    body.addObject("RestShapeSpringsForceField", points=roi.indices.getLinkPath(), stiffness=1e6)
    body.addObject("TetrahedronFEMForceField", youngModulus=1e4, poissonRatio=0.3)
    body.addObject("OglModel", color=[0.0, 0.7, 0.7, 1])  # numbers for a text
    rigid = root.addChild("rigid")
    rigid.addObject("MechanicalObject", name="mstate", template="Rigid3", translation2=[0, 1, 0])
    rigid.addObject("UniformMass", name="mass", vertexMass=[1.0, 1.0, [1, 0, 0, 0, 1, 0, 0, 0, 1]])  # ragged, as STLIB
    Sofa.Simulation.init(root)
    Sofa.Simulation.animate(root, 0.01)
    assert len(body.dofs.position.value) > 4


def test_what_softrobots_tutorials_write(tmp_path):
    """SoftRobots' Tripod and thematic docs: an STL loader's points for a MechanicalObject, a Vec1
    state's rows, an integer for a bool (as SOFA reads "1")."""
    stl = tmp_path / "square.stl"
    facets = [((0, 0, 0), (1, 0, 0), (0, 1, 0)), ((1, 0, 0), (1, 1, 0), (0, 1, 0))]
    stl.write_text("solid square\n" + "".join(
        "facet normal 0 0 1\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in facet) + "endloop\nendfacet\n"
        for facet in facets) + "endsolid square\n")
    root = Sofa.Core.Node("root")
    body = root.addChild("body")
    body.addObject("EulerImplicitSolver")
    body.addObject("CGLinearSolver", iterations=10, tolerance=1e-9, threshold=1e-9)
    loader = body.addObject("MeshSTLLoader", name="loader", filename=str(stl))
    body.addObject("MechanicalObject", name="dofs", position=loader.position.getLinkPath(), rotation=[90, 0, 0])
    body.addObject("UniformMass", totalMass=1)
    angle = root.addChild("angle")
    angle.addObject("MechanicalObject", name="dofs", template="Vec1", position=[[0]], rest_position=[[0.5]])
    assert angle.dofs.position.value.tolist() == [[0.0]]
    assert angle.dofs.rest_position.value.tolist() == [[0.5]]
    tet = root.addChild("tet")
    tet.addObject("TetrahedronSetTopologyContainer", name="topology", tetrahedra=[0, 1, 2, 3], createTriangleArray=1)
    assert tet.topology.createTriangleArray.value is True
    with pytest.raises(TypeError, match="expected True or False"):
        tet.topology.createTriangleArray = 2
    Sofa.Simulation.init(root)
    Sofa.Simulation.animate(root, 0.01)
    # The file's four distinct points, turned a quarter about x, after one step of free fall.
    expected = np.array([[0, 0, 0], [1, 0, 0], [0, 0, 1], [1, 0, 1]], dtype=float)
    moved = body.dofs.position.value
    assert moved.shape == (4, 3)
    np.testing.assert_allclose(moved[:, [0, 2]], expected[:, [0, 2]], atol=1e-12)
    assert np.all(moved[:, 1] < 0)


def _stlib_scene(second_parent):
    """STLIB's Scene: the body in root/Modelling, the solvers in root/Simulation, and (second_parent)
    Simulation.addChild(Modelling); or the body written under Simulation directly."""
    root = Sofa.Core.Node("root")
    root.gravity = [0, -9.81, 0]
    simulation = root.addChild("Simulation")
    simulation.addObject("EulerImplicitSolver", rayleighStiffness=0.1, rayleighMass=0.1)
    simulation.addObject("SparseLDLSolver")
    modelling = root.addChild("Modelling") if second_parent else simulation.addChild("Modelling")
    modelling.addObject("RegularGridTopology", name="grid", n=[5, 2, 2], min=[0, 0, 0], max=[1, 0.2, 0.2])
    body = modelling.addChild("body")
    body.addObject("MechanicalObject", name="dofs", position=modelling.grid.position.getLinkPath())
    body.addObject("UniformMass", totalMass=1)
    body.addObject("TetrahedronFEMForceField", youngModulus=1e4, poissonRatio=0.3,
                   topology=modelling.grid.getLinkPath())
    roi = modelling.addChild("box")
    roi.addObject("BoxROI", name="roi", box=[-0.01, -0.01, -0.01, 0.01, 0.21, 0.21], position=body.dofs.rest_position.getLinkPath())
    held = roi.addChild("held")
    body.addChild(held)  # FixingBox: the springs below the body as well
    held.addObject("RestShapeSpringsForceField", points=roi.roi.indices.getLinkPath(), stiffness=1e8)
    if second_parent:
        simulation.addChild(modelling)
    return root


def test_a_node_with_a_second_parent_moves_below_it_and_keeps_its_links():
    moved, written = _stlib_scene(True), _stlib_scene(False)
    assert moved.Modelling is moved.Simulation.Modelling  # still found from its first parent
    assert moved.Modelling.getPathName() == "/Simulation/Modelling"
    assert moved.Simulation.Modelling.box.held.getPathName() == "/Simulation/Modelling/body/held"
    for root in (moved, written):
        Sofa.Simulation.init(root)
        for _ in range(20):
            Sofa.Simulation.animate(root, 0.01)
    a = moved.Simulation.Modelling.body.dofs.position.value
    b = written.Simulation.Modelling.body.dofs.position.value
    assert np.array_equal(a, b)
    assert np.all(np.abs(a[0] - [0, 0, 0]) < 1e-6) and a[4][1] < -1e-3  # held at x = 0, sagging at the tip
    with pytest.raises(ValueError, match="cycle"):
        moved.Simulation.Modelling.body.addChild(moved.Simulation)


def _held_beam():
    """A beam held at its left end by stiff rest-shape springs (SoftRobots' grippers hold their
    fingers so), and a rigid goal pulled to its rest by springs (the Tripod's maze)."""
    root = Sofa.Core.Node("root")
    root.gravity = [0, -9.81, 0]
    beam = root.addChild("beam")
    beam.addObject("EulerImplicitSolver", rayleighStiffness=0.1, rayleighMass=0.1)
    beam.addObject("SparseLDLSolver")
    beam.addObject("RegularGridTopology", name="grid", n=[5, 2, 2], min=[0, 0, 0], max=[1, 0.2, 0.2])
    beam.addObject("MechanicalObject", name="dofs")
    beam.addObject("UniformMass", totalMass=1)
    beam.addObject("TetrahedronFEMForceField", youngModulus=1e4, poissonRatio=0.3)
    beam.addObject("BoxROI", name="box", box=[-0.01, -0.01, -0.01, 0.01, 0.21, 0.21])
    beam.addObject("RestShapeSpringsForceField", points=beam.box.indices.linkpath, stiffness=1e7)
    goal = root.addChild("goal")
    goal.addObject("EulerImplicitSolver", firstOrder=True)
    goal.addObject("CGLinearSolver", iterations=100, tolerance=1e-12, threshold=1e-12)
    goal.addObject("MechanicalObject", name="dofs", template="Rigid3", position=[0, 0, 0, 0, 0, 0, 1])
    goal.addObject("UniformMass", totalMass=1)
    goal.addObject("RestShapeSpringsForceField", points=0, stiffness=1e5, angularStiffness=1e5)
    return root


def test_rest_positions_written_by_a_script_move_the_springs_anchors():
    import math

    root = _held_beam()
    Sofa.Simulation.init(root)
    dofs = root.beam.dofs
    start = dofs.position.value.copy()
    rest = dofs.rest_position.value.copy()
    for _ in range(100):  # SoftRobots' gripper controllers: the whole rest shape moved 1 mm a step
        rest[:, 0] += 0.001
        dofs.rest_position.value = rest
        Sofa.Simulation.animate(root, 0.01)
    for _ in range(200):  # then still: the body settles where the springs now hold it
        Sofa.Simulation.animate(root, 0.01)
    np.testing.assert_allclose(dofs.rest_position.value, rest)
    held = [0, 5, 10, 15]  # the left end's points (x = 0)
    np.testing.assert_allclose(dofs.position.value[held, 0], start[held, 0] + 0.1, atol=1e-4)
    # The FEM keeps its rest shape of init (as SOFA's): the beam is carried along, not stretched; it
    # ends as the same beam left in place, moved by 0.1 along x.
    still = _held_beam()
    Sofa.Simulation.init(still)
    for _ in range(300):
        Sofa.Simulation.animate(still, 0.01)
    np.testing.assert_allclose(dofs.position.value - [0.1, 0, 0], still.beam.dofs.position.value, atol=1e-4)
    # A rigid's rest pose: its springs pull it there (centre and orientation).
    half = math.radians(30) / 2
    root.goal.dofs.rest_position.value = [[0.5, 0.2, 0, 0, 0, math.sin(half), math.cos(half)]]
    for _ in range(200):
        Sofa.Simulation.animate(root, 0.01)
    sag = 9.81 * 1 / 1e5  # its weight on the springs
    np.testing.assert_allclose(root.goal.dofs.position.value[0], [0.5, 0.2 - sag, 0, 0, 0, math.sin(half), math.cos(half)],
                               atol=1e-7)
    with pytest.raises(ValueError, match="rest_position"):
        root.goal.dofs.rest_position.value = [[0, 0, 0]]


def test_outputs_read_before_init_are_computed_or_warned_empty():
    root = Sofa.Core.Node("root")
    body = root.addChild("body")
    body.addObject("RegularGridTopology", name="grid", n=[3, 2, 2], min=[0, 0, 0], max=[2, 1, 1])
    body.addObject("MechanicalObject", name="dofs")
    roi = body.addObject("BoxROI", name="roi", box=[-0.1, -0.1, -0.1, 0.1, 1.1, 1.1])
    assert roi.indices.value.tolist() == [0, 3, 6, 9]  # the x = 0 face, x fastest
    assert roi.nbIndices.value == 4
    missing = body.addObject("MeshOBJLoader", name="missing", filename="no/such/file.obj")
    with pytest.warns(SceneWarning, match=r"missing.position: .*no/such/file.obj"):
        points = missing.position.value
    assert points.shape == (0, 3)


def test_data_set_parent_follows_the_parent():
    """SofaPython3's Data.setParent, as STLIB's servomotor prefabs link their angles."""

    class Holder(Sofa.Core.Controller):
        def __init__(self, *args, **kwargs):
            Sofa.Core.Controller.__init__(self, *args, **kwargs)
            self.addData(name="angle", type="float", value=0.0, help="an angle", group="")

    root = Sofa.Core.Node("root")
    source = root.addObject(Holder(name="source"))
    follower = root.addObject(Holder(name="follower"))
    assert not follower.angle.hasParent()
    follower.angle.setParent(source.angle)
    assert follower.angle.hasParent() and follower.angle.getParent().getLinkPath() == source.angle.getLinkPath()
    source.angle.value = 1.5
    assert follower.angle.value == 1.5
    # A component's datum: the link goes into the scene (its value for a datum a script made).
    state = root.addObject("MechanicalObject", name="dofs", position=[[0, 0, 0]])
    mass = root.addObject("UniformMass", name="mass", totalMass=1)
    mass.totalMass.setParent(source.angle)
    assert mass.totalMass.value == 1.5
    with pytest.raises(ValueError, match="its own parent"):
        state.position.setParent(state.position)
