"""Sofa.Gui: SofaPython3's GUIManager opens fastcorot's viewer (`fastcorot view`) on the scene of
the root it is given, whatever the GUI name (imgui, qglviewer, ...). Without a display it raises
RuntimeError saying so (use xvfb-run, or `fastcorot run script.py --png DIR` for pictures).
FASTCOROT_VIEW_FRAMES=N closes the window after N frames (as `fastcorot view --frames N`)."""

import os

from fastcorot import _core

from . import _script
from .Core import Node


class _NamesCalls(type):
    def __getattr__(cls, name):
        raise AttributeError(f"Sofa.Gui.GUIManager.{name}: SofaPython3's GUI has it, fastcorot's viewer does not (it has "
                             "Init, createGUI, SetDimension, MainLoop, closeGUI)")


class GUIManager(metaclass=_NamesCalls):
    _size = (1280, 720)
    _script = None

    @staticmethod
    def Init(program_name="", gui_name=""):
        """Accepted (fastcorot has one viewer)."""
        return 0

    @staticmethod
    def ListSupportedGUI(separator=" "):
        return "fastcorot"

    @staticmethod
    def createGUI(root, filename=""):
        GUIManager._script = filename or None
        return 0

    @staticmethod
    def SetDimension(width, height):
        GUIManager._size = (int(width), int(height))

    @staticmethod
    def MainLoop(root, filename=""):
        """Shows the scene of `root` (initialised) in the viewer until the window is closed."""
        if not isinstance(root, Node):
            raise TypeError(f"Sofa.Gui.GUIManager.MainLoop: expected a Sofa.Core.Node, got {type(root).__name__}")
        script = filename or GUIManager._script or "scene.py"
        if not script.endswith(".py"):
            script += ".py"
        run = _script.ScriptRun(root.getRoot(), script)
        run.core  # raises when the root is not initialised
        arguments = ["fastcorot", "view", script, "--size", "{}x{}".format(*GUIManager._size)]
        frames = os.environ.get("FASTCOROT_VIEW_FRAMES")
        if frames:
            arguments += ["--frames", frames]
        status = _core.cli_main(arguments, lambda path, strict: run)
        if status != 0:
            raise RuntimeError("Sofa.Gui.GUIManager.MainLoop: fastcorot's viewer could not show the scene (its message "
                               "is above; without a display use xvfb-run, or `fastcorot run SCRIPT --png DIR`)")
        return 0

    @staticmethod
    def closeGUI():
        """Accepted: the window closes when MainLoop returns."""
