"""Sofa: SofaPython3's API over fastcorot, so that a script written for SofaPython3 runs unchanged.

    import Sofa
    root = Sofa.Core.Node("root")
    createScene(root)                  # root.addChild / addObject, Data .value, controllers
    Sofa.Simulation.initRoot(root)
    Sofa.Simulation.animate(root, root.dt.value)

The scene is a fastcorot scene tree (`root.fastcorot_node`): `fastcorot run script.py` and
`fastcorot view script.py` call the script's createScene(root) and run it as they run a .scn file.
What SofaPython3 has and fastcorot does not is a clear exception naming it. docs/python.md has the
table of what maps and what differs.
"""

from . import Core, Helper, Simulation, constants  # noqa: F401  (Sofa.Gui is imported on demand, as in SofaPython3)

from ._prefab import Prefab  # noqa: E402

__all__ = ["Core", "Helper", "Prefab", "Simulation", "constants"]


def _located(kind):
    def message(target, text):
        """SofaPython3's Sofa.msg_*(target, message): Sofa.Helper's message with the caller's file and line."""
        import sys

        caller = sys._getframe(1)  # the caller's frame alone (inspect.stack() reads every frame's source)
        Helper._message(kind, (target, f"{text} ({caller.f_code.co_filename}:{caller.f_lineno})"))

    message.__name__ = "msg_" + kind.lower()
    return message


msg_info = _located("INFO")
msg_warning = _located("WARNING")
msg_error = _located("ERROR")
msg_deprecated = _located("DEPRECATED")


def __getattr__(name):
    raise AttributeError(f"Sofa.{name}: SofaPython3 has it, fastcorot's Sofa package does not (docs/python.md lists what "
                         "maps)")
