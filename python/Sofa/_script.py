"""Scene scripts as scenes of the command line: `fastcorot run script.py` (and `view`) load the script
as runSofa does (its folder on sys.path, `__name__` not "__main__", so its main() does not run),
call createScene(root), build the simulation, and call its controllers around each step. Every
failure is a ScriptError with one line naming the script's file and line."""

import importlib.util
import os
import sys
import traceback
import warnings

from fastcorot.scene import SceneWarning

from . import Core, Simulation


class ScriptError(Exception):
    """A script failed: one line naming where (the script's file and line) and what."""


def _one_line(error, script):
    """`error` as one line, with the innermost place of the script it came from."""
    text = " ".join(str(error).split()) or type(error).__name__
    if text.startswith(os.path.abspath(script)) or text.startswith(script):
        return text  # fastcorot's own errors name the script's line already
    frames = [f for f in traceback.extract_tb(error.__traceback__) if os.path.abspath(f.filename) == os.path.abspath(script)]
    where = f"{script}:{frames[-1].lineno}" if frames else script
    return f"{where}: {type(error).__name__}: {text}"


def _import(script):
    if not os.path.isfile(script):
        raise ScriptError(f"{script}: no such file")
    folder = os.path.dirname(os.path.abspath(script))
    if folder not in sys.path:
        sys.path.insert(0, folder)
    name = "fastcorot_scene_" + os.path.splitext(os.path.basename(script))[0].replace("-", "_")
    spec = importlib.util.spec_from_file_location(name, script)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    try:
        spec.loader.exec_module(module)
    except Exception as error:
        raise ScriptError(_one_line(error, script)) from None
    if not callable(getattr(module, "createScene", None)):
        raise ScriptError(f"{script}: defines no createScene(root): the function runSofa and fastcorot call to build "
                          "the scene")
    return module


class ScriptRun:
    """The running scene of a script (or of a root built by hand, for Sofa.Gui): what the command
    line calls (core, begin_step, end_step, key_pressed, reload, has_controllers)."""

    def __init__(self, root, script, rebuild=None):
        self.root = root
        self.script = script
        self._rebuild = rebuild

    @property
    def core(self):
        return Simulation.simulation_of(self.root)._core

    @property
    def has_controllers(self):
        return bool(self.root._all_controllers())

    def _send(self, event_type, **fields):
        try:
            self.root._send(event_type, **fields)
        except Exception as error:
            raise ScriptError(_one_line(error, self.script) + f" (in a controller's {event_type})") from None
        finally:
            sys.stdout.flush()

    def begin_step(self):
        self._send("AnimateBeginEvent", dt=self.core.dt)
        if self.root._extra.get("_grown"):  # a controller changed the tree and did not init() it
            try:
                Simulation._regrow(self.root)
            except Exception as error:
                raise ScriptError(_one_line(error, self.script) + " (building the scene again after a controller changed it)") from None

    def end_step(self):
        self._send("AnimateEndEvent", dt=self.core.dt)

    def key_pressed(self, key):
        self._send("KeypressedEvent", key=key)
        if self.root._extra.get("_grown"):
            try:
                Simulation._regrow(self.root)
            except Exception as error:
                raise ScriptError(_one_line(error, self.script) + " (building the scene again after a controller changed it)") from None

    def reload(self):
        if self._rebuild is None:
            Simulation.reset(self.root)
        else:
            self.root = self._rebuild().root


def build(script, strict=False):
    """The root of `script`'s scene: createScene(root) on a new Sofa.Core.Node("root")."""
    module = _import(script)
    root = Core.Node("root")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SceneWarning)  # the command line prints the builder's warnings
        try:
            module.createScene(root)
        except Exception as error:
            raise ScriptError(_one_line(error, script)) from None
    return root


def load(script, strict=False):
    """The running scene of `script` for the command line (the scene built, controllers' init() called)."""
    def rebuild():
        root = build(script, strict)
        try:
            Simulation._start(root, strict)
        except Exception as error:
            raise ScriptError(_one_line(error, script)) from None
        return ScriptRun(root, script, rebuild)

    return rebuild()
