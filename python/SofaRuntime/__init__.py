"""SofaRuntime: SofaPython3's plugin loading. fastcorot's components are built in, so importPlugin
accepts every name (a component the plugin would bring and fastcorot lacks is refused where the
scene adds it, naming it)."""

import sys

import Sofa  # noqa: F401  (SofaRuntime makes Sofa importable in SofaPython3 too)


def importPlugin(name):
    """Accepted: fastcorot's components need no plugin."""
    return True


def init():
    """Accepted."""


class PluginRepository:
    @staticmethod
    def addFirstPath(path):
        """Accepted."""


class DataRepository:
    @staticmethod
    def addFirstPath(path):
        """Data files resolve as in scene files: the script's folder, then FASTCOROT_DATA_PATH, then
        the share/ and examples/ folders of the nearest ancestor (docs/sofa-components.md)."""


def getPythonCallingPoint():
    frame = sys._getframe(1)
    return f"{frame.f_code.co_filename}:{frame.f_lineno}"
