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
    """Where data files are found, as in scene files: the script's folder, then FASTCOROT_DATA_PATH,
    then the folders added here or by AddDataRepository, then the share/ and examples/ folders of the
    nearest ancestor (docs/sofa-components.md)."""

    @staticmethod
    def addFirstPath(path):
        """Adds `path` (relative: to the current folder) to the folders searched (after FASTCOROT_DATA_PATH)."""
        import os

        from fastcorot import _core

        _core.add_data_repository(os.path.abspath(str(path)))

    addLastPath = addFirstPath

    @staticmethod
    def getFile(name):
        """The full path of data file `name` as a scene in the current folder would find it (`name`
        itself when nothing is found, as SOFA returns it)."""
        import os

        from fastcorot import _core

        try:
            return str(_core.find_data_file(os.path.join(os.getcwd(), "scene.py"), str(name)))
        except (ValueError, FileNotFoundError):
            return str(name)


def getPythonCallingPoint():
    frame = sys._getframe(1)
    return f"{frame.f_code.co_filename}:{frame.f_lineno}"
