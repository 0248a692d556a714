"""The Sofa compatibility package: SofaPython3 scripts run unchanged (docs/python.md)."""

import json
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

import Sofa
import Sofa.Simulation
from fastcorot.scene import SceneWarning

from conftest import REPOSITORY, dump_state, executable, run_cli

SOFA_BEAM = REPOSITORY / "examples/python/sofa_beam.py"
BEAM_SCN = REPOSITORY / "examples/cantilever_beam_40x10x10.scn"
SOFA_SCENES = REPOSITORY / "../shared/sofa-scenes"
PYTHON_EXAMPLES = SOFA_SCENES / "python/examples"


def load_script(path, name):
    import importlib.util

    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def beam_root():
    root = Sofa.Core.Node("root")
    load_script(SOFA_BEAM, "sofa_beam").createScene(root)
    return root


def tetrahedron_scene(root, controller=None):
    """Four points, one tetrahedron, point 0 fixed: a small scene for the calls below."""
    root.dt = 0.01
    node = root.addChild("body")
    node.addObject("EulerImplicitSolver")
    node.addObject("EigenSimplicialLDLT")
    state = node.addObject("MechanicalObject", name="dofs", position=[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    node.addObject("TetrahedronSetTopologyContainer", name="topology", tetrahedra=[0, 1, 2, 3])
    node.addObject("UniformMass", name="mass", totalMass=2)
    node.addObject("FastTetrahedralCorotationalForceField", name="FEM", youngModulus=100, poissonRatio=0.3)
    node.addObject("FixedProjectiveConstraint", name="fixed", indices=[0])
    if controller is not None:
        node.addObject(controller)
    return state


# --- the same trajectories as the scene files -----------------------------------------------------------

def test_a_sofapython3_script_steps_bitwise_as_its_scn_file(tmp_path):
    expected = dump_state(BEAM_SCN, [1, 10, 100], tmp_path)
    out = tmp_path / "script.json"
    run_cli("run", "--quiet", SOFA_BEAM, "--steps", 100, "--dump-state", out, "--dump-steps", "1,10,100")
    from_script = {int(k): v for k, v in json.loads(out.read_text())["steps"].items()}
    assert from_script == expected
    # And in-process, through Sofa.Simulation.animate.
    root = beam_root()
    Sofa.Simulation.init(root)
    for _ in range(10):
        Sofa.Simulation.animate(root, root.dt.value)
    assert np.array_equal(root.beam.state.position.array(), np.array(expected[10]["root/beam"]))


@pytest.mark.skipif(not PYTHON_EXAMPLES.is_dir(), reason="no ../shared/sofa-scenes")
def test_liver_py_steps_bitwise_as_its_xml_transcription(tmp_path):
    mesh = (SOFA_SCENES / "share/mesh").resolve()
    scene = tmp_path / "liver.scn"
    scene.write_text(f"""<Node name="root" gravity="0 -9.81 0" dt="0.02">
  <DefaultAnimationLoop/>
  <CollisionPipeline/><BruteForceBroadPhase/><BVHNarrowPhase/>
  <CollisionResponse response="PenalityContactForceField"/><DiscreteIntersection/>
  <MeshOBJLoader name="LiverSurface" filename="{mesh}/liver-smooth.obj"/>
  <Node name="Liver">
    <EulerImplicitSolver rayleighStiffness="0.1" rayleighMass="0.1"/>
    <CGLinearSolver iterations="25" tolerance="1e-09" threshold="1e-09"/>
    <MeshGmshLoader name="meshLoader" filename="{mesh}/liver.msh"/>
    <TetrahedronSetTopologyContainer name="topo" src="@meshLoader"/>
    <MechanicalObject name="dofs" src="@meshLoader"/>
    <TetrahedronSetGeometryAlgorithms template="Vec3d"/>
    <DiagonalMass massDensity="1.0"/>
    <TetrahedralCorotationalFEMForceField method="large" poissonRatio="0.3" youngModulus="3000" computeGlobalMatrix="0"/>
    <FixedProjectiveConstraint indices="3 39 64"/>
    <Node name="Visu"><OglModel name="VisualModel" src="@../../LiverSurface"/><BarycentricMapping input="@../dofs" output="@VisualModel"/></Node>
  </Node>
</Node>""")
    expected = dump_state(scene, [1, 100], tmp_path)
    out = tmp_path / "liver.json"
    run_cli("run", PYTHON_EXAMPLES / "liver.py", "--steps", 100, "--quiet", "--dump-state", out, "--dump-steps", "1,100")
    assert {int(k): v for k, v in json.loads(out.read_text())["steps"].items()} == expected


# --- SofaPython3's examples ----------------------------------------------------------------------------

# What each example does with `fastcorot run SCRIPT --steps 100`: runs, or is refused naming what is missing.
EXAMPLES = {
    "liver.py": None,
    "liver-scriptcontroller.py": None,
    "basic.py": None,
    "emptyController.py": None,
    "emptyForceField.py": None,
    "springForceField.py": None,
    "access_matrix.py": None,
    "access_stiffness_matrix.py": None,
    "access_mass_matrix.py": None,
}


@pytest.mark.skipif(not PYTHON_EXAMPLES.is_dir(), reason="no ../shared/sofa-scenes")
@pytest.mark.parametrize("script", sorted(EXAMPLES))
def test_sofapython3_examples_run_or_are_refused_in_one_line(script, tmp_path):
    path = PYTHON_EXAMPLES / script
    missing = EXAMPLES[script]
    out = tmp_path / "state.json"
    # springForceField.py draws SOFA's mesh/ball.obj and mesh/floor.obj, which ../shared does not
    # hold: a data folder with two small surfaces of those names stands in for SOFA's share/.
    data = tmp_path / "data" / "mesh"
    data.mkdir(parents=True)
    for name in ("ball.obj", "floor.obj"):
        (data / name).write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    env = dict(os.environ, FASTCOROT_DATA_PATH=str(tmp_path / "data"))
    completed = subprocess.run([str(executable()), "run", str(path), "--steps", "100", "--quiet", "--dump-state", str(out)],
                               capture_output=True, text=True, timeout=300, cwd=tmp_path, env=env)
    if missing is None:
        assert completed.returncode == 0, completed.stderr
        for points in json.loads(out.read_text())["steps"]["100"].values():
            assert np.all(np.isfinite(points))
    else:
        assert completed.returncode == 2, completed.stderr
        lines = [line for line in completed.stderr.splitlines() if not line.startswith(("info:", "warning:"))]
        assert len(lines) == 1 and lines[0].startswith("fastcorot: error: ") and missing in lines[0], completed.stderr


@pytest.mark.skipif(not PYTHON_EXAMPLES.is_dir(), reason="no ../shared/sofa-scenes")
def test_the_examples_own_main_runs_with_the_gui_switched_off(capsys):
    liver = load_script(PYTHON_EXAMPLES / "liver.py", "liver_example")
    liver.USE_GUI = False
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SceneWarning)
        liver.main()
    env = dict(os.environ, PYTHONPATH=os.environ.get("PYTHONPATH", str(REPOSITORY / "build/python")))
    completed = subprocess.run([sys.executable, str(PYTHON_EXAMPLES / "basic.py")], capture_output=True, text=True,
                               timeout=120, env=env)
    assert completed.returncode == 0, completed.stderr
    assert "Simulation made 10 time steps. Done" in completed.stdout


def test_gui_calls_without_a_display_raise_a_clear_error(monkeypatch):
    import Sofa.Gui

    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    root = Sofa.Core.Node("root")
    tetrahedron_scene(root)
    Sofa.Simulation.init(root)
    Sofa.Gui.GUIManager.Init("myscene", "imgui")
    Sofa.Gui.GUIManager.createGUI(root, __file__)
    with pytest.raises(RuntimeError, match="viewer could not show the scene"):
        Sofa.Gui.GUIManager.MainLoop(root)


# --- the command line ---------------------------------------------------------------------------------

def test_script_errors_are_one_line_with_status_2(tmp_path):
    script = tmp_path / "broken.py"
    script.write_text("import Sofa\n\nclass C(Sofa.Core.Controller):\n"
                      "    def onAnimateEndEvent(self, event):\n        raise ValueError('boom')\n\n"
                      "def createScene(root):\n    root.addObject(C(name='c'))\n")
    completed = subprocess.run([str(executable()), "run", str(script), "--steps", "3"], capture_output=True, text=True)
    assert completed.returncode == 2
    assert f"{script}:5: ValueError: boom (in a controller's AnimateEndEvent)" in completed.stderr
    empty = tmp_path / "empty.py"
    empty.write_text("x = 1\n")
    completed = subprocess.run([str(executable()), "run", str(empty)], capture_output=True, text=True)
    assert completed.returncode == 2 and "defines no createScene(root)" in completed.stderr
    moved = subprocess.run([str(executable()), "run", str(SOFA_BEAM)], capture_output=True, text=True,
                           env=dict(os.environ, FASTCOROT_PYTHONPATH=str(tmp_path / "nowhere")))
    assert moved.returncode == 2 and "the Python module, which is not in" in moved.stderr
    checkpoint = tmp_path / "c.ckpt"
    run_cli("run", SOFA_BEAM, "--steps", 4, "--quiet", "--checkpoint-every", 2, "--checkpoint", checkpoint)
    completed = subprocess.run([str(executable()), "run", str(SOFA_BEAM), "--steps", "6", "--resume", str(checkpoint)],
                               capture_output=True, text=True)
    assert completed.returncode == 2 and "Python controllers" in completed.stderr
    with_field = tmp_path / "field.py"
    with_field.write_text("import Sofa\n\nclass F(Sofa.Core.ForceFieldVec3d):\n"
                          "    def addForce(self, m, f, x, v):\n        pass\n\n"
                          "    def addDForce(self, m, df, dx):\n        pass\n\n"
                          "def createScene(root):\n    n = root.addChild('n')\n    n.addObject('EulerImplicitSolver')\n"
                          "    n.addObject('CGLinearSolver')\n    n.addObject('MechanicalObject', position=[0, 0, 0])\n"
                          "    n.addObject('UniformMass', totalMass=1)\n    n.addObject(F(name='f'))\n")
    completed = subprocess.run([str(executable()), "run", str(with_field), "--steps", "2", "--checkpoint-every", "1",
                                "--checkpoint", str(tmp_path / "f.ckpt")], capture_output=True, text=True)
    assert completed.returncode == 2 and "Python ForceField 'f' carries its Python state" in completed.stderr


# --- the viewer ---------------------------------------------------------------------------------------

def _xvfb(arguments, env=None, tmp_path=None):
    import shutil

    if shutil.which("xvfb-run") is None:
        pytest.skip("no xvfb-run")
    completed = subprocess.run(["xvfb-run", "-a", *arguments], capture_output=True, text=True, timeout=300, env=env,
                               cwd=tmp_path)
    if completed.returncode != 0 and "FASTCOROT_BUILD_VIEWER" in completed.stderr:
        pytest.skip("built without the viewer")
    return completed


def test_a_script_in_the_viewer_and_through_sofa_gui(tmp_path):
    shot = tmp_path / "shot.png"
    completed = _xvfb([str(executable()), "view", str(SOFA_BEAM), "--frames", "20", "--screenshot", str(shot)],
                      tmp_path=tmp_path)
    assert completed.returncode == 0, completed.stderr
    assert "20 steps, 20 frames" in completed.stdout and shot.stat().st_size > 1000
    script = tmp_path / "gui.py"
    script.write_text(f"""import sys
sys.path.insert(0, {str(SOFA_BEAM.parent)!r})
import Sofa, Sofa.Simulation, Sofa.Gui, SofaImGui
import sofa_beam
root = Sofa.Core.Node("root")
sofa_beam.createScene(root)
Sofa.Simulation.init(root)
Sofa.Gui.GUIManager.Init("myscene", "imgui")
Sofa.Gui.GUIManager.createGUI(root, sofa_beam.__file__)
Sofa.Gui.GUIManager.SetDimension(320, 240)
Sofa.Gui.GUIManager.MainLoop(root)
Sofa.Gui.GUIManager.closeGUI()
print("steps", Sofa.Simulation.simulation_of(root).steps_done, "tip controller", root.beam.tip.steps)
""")
    env = dict(os.environ, FASTCOROT_VIEW_FRAMES="15")
    completed = _xvfb([sys.executable, str(script)], env=env, tmp_path=tmp_path)
    assert completed.returncode == 0, completed.stderr
    assert "steps 15 tip controller 15" in completed.stdout


def test_keys_reach_the_controllers_as_keypressed_events():
    from Sofa import _script

    pressed = []

    class Keys(Sofa.Core.Controller):
        def onKeypressedEvent(self, event):
            pressed.append(event["key"])

    root = Sofa.Core.Node("root")
    tetrahedron_scene(root, Keys(name="keys"))
    Sofa.Simulation.init(root)
    run = _script.ScriptRun(root, "keys.py")
    run.key_pressed("L")
    assert pressed == ["L"] and run.has_controllers


def test_flat_lists_are_read_as_sofapython3_passes_them():
    # SofaPython3 writes a list as SOFA's text, its numbers in a row: a flat position list is the
    # same points as the nested one, and a nested vector reads as its numbers.
    nested, flat = Sofa.Core.Node("root"), Sofa.Core.Node("root")
    a = tetrahedron_scene(nested)
    body = flat.addChild("body")
    body.addObject("EulerImplicitSolver")
    body.addObject("EigenSimplicialLDLT")
    b = body.addObject("MechanicalObject", name="dofs", position=[0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1])
    body.addObject("TetrahedronSetTopologyContainer", name="topology", tetrahedra=[0, 1, 2, 3])
    body.addObject("UniformMass", name="mass", totalMass=2)
    body.addObject("FastTetrahedralCorotationalForceField", name="FEM", youngModulus=100, poissonRatio=0.3)
    body.addObject("FixedProjectiveConstraint", name="fixed", indices=[0])
    flat.gravity = [[0, -9.81, 0]]
    nested.gravity = [0, -9.81, 0]
    Sofa.Simulation.init(nested)
    Sofa.Simulation.init(flat)
    for _ in range(5):
        Sofa.Simulation.animate(nested, 0.01)
        Sofa.Simulation.animate(flat, 0.01)
    assert np.array_equal(a.position.array(), b.position.array())
    with pytest.raises(ValueError, match=r"position: expected an \(n, 3\) array of numbers, got shape \(4,\)"):
        body.addObject("MechanicalObject", name="odd", position=[0, 0, 0, 1])
