"""Components written in Python, as SofaPython3 has them: Controller (called by the animation loop)
and ForceField (called by the solvers, through python/src/python_force_field.cpp). Both have a
name, their node (getContext) and data of their own (addData). Sofa.Core exports them."""

from ._data import Data


# SOFA's Base and BaseObject data that a component written in Python has too (name apart), with
# their defaults; SofaPython3 sets `listening` for every Python component.
_BASE_DATA = {"listening": True, "printLog": False, "tags": "", "bbox": "", "componentState": "Valid"}


class _PythonComponent:
    """What a component written in Python has of SOFA's BaseObject: a name, SOFA's base data
    (listening, printLog, tags) and the node it is in. As SofaPython3, a keyword argument naming a
    datum sets it and the others are ignored; ``self.name = ...`` and ``self.listening = ...`` set them."""

    def __init__(self, *args, **kwargs):
        name = kwargs.get("name")
        if name is None:
            name = args[0] if args and isinstance(args[0], str) else type(self).__name__
        self.__dict__["_sofa_name"] = str(name.value if isinstance(name, Data) else name)
        self.__dict__["_sofa_context"] = None
        self.__dict__["_sofa_base"] = {key: kwargs.get(key, default) for key, default in _BASE_DATA.items()}

    def init(self):
        """Called once the simulation is built (Sofa.Simulation.init)."""

    def reinit(self):
        pass

    def _base_data(self):
        return self.__dict__.setdefault("_sofa_base", dict(_BASE_DATA))  # also for a subclass that skipped __init__

    def getName(self):
        return self._sofa_name

    def setName(self, name):
        self._set_data_value("name", name)

    def getClassName(self):
        return type(self).__name__

    def getTemplateName(self):
        return ""

    def getData(self, name):
        """The datum `name` (None when the component has none), as SofaPython3's getData/findData."""
        return Data(self, name) if name == "name" or name in _BASE_DATA or name in self.__dict__.get("_sofa_data", {}) else None

    findData = getData

    def getDataFields(self):
        return [Data(self, name) for name in ["name", *_BASE_DATA, *self.__dict__.get("_sofa_data", {})]]

    def getContext(self):
        return self._sofa_context

    def getPathName(self):
        context = self._sofa_context
        return context._sofa_path(self._sofa_name) if context is not None else "/" + self._sofa_name

    def getLinkPath(self):
        return "@" + self.getPathName()

    @property
    def name(self):
        return Data(self, "name")

    @name.setter
    def name(self, value):
        self._set_data_value("name", value.value if isinstance(value, Data) else value)

    def addData(self, name, value=None, default=None, help="", group="", type=""):
        """A datum of the component's own (SofaPython3's addData): then ``self.<name>`` is a Data with
        `.value`, and other objects may link to it."""
        if not isinstance(name, str) or not name.isidentifier():
            raise TypeError(f"{self.getPathName()}: addData: name must be an identifier, got {name!r}")
        self.__dict__.setdefault("_sofa_data", {})[name] = value if value is not None else default
        return Data(self, name)

    def __getattr__(self, name):
        own = self.__dict__.get("_sofa_data", {})
        if name in own or name in _BASE_DATA:
            return Data(self, name)
        raise AttributeError(f"{type(self).__name__} '{self.__dict__.get('_sofa_name', '?')}' has no attribute '{name}'")

    def __setattr__(self, name, value):
        own = self.__dict__.get("_sofa_data", {})
        if name in own:
            own[name] = value.value if isinstance(value, Data) else value
        elif name in _BASE_DATA and name not in self.__dict__:
            self._base_data()[name] = value.value if isinstance(value, Data) else value
        else:
            object.__setattr__(self, name, value)

    # the owner protocol of Data
    def _data_value(self, name):
        if name == "name":
            return self._sofa_name
        if name in _BASE_DATA and name not in self.__dict__.get("_sofa_data", {}):
            return self._base_data()[name]
        own = self.__dict__.get("_sofa_data", {})
        if name in own:
            return own[name]
        raise AttributeError(f"{self.getPathName()}: no datum '{name}' (add one with addData)")

    def _set_data_value(self, name, value):
        own = self.__dict__.get("_sofa_data", {})
        if name in own:
            own[name] = value
            return
        if name in _BASE_DATA:
            self._base_data()[name] = value
            return
        if name != "name" or not isinstance(value, str):
            raise TypeError(f"{self.getPathName()}: a Python component's data are its name (a str), "
                            f"{', '.join(_BASE_DATA)} and those of addData")
        self.__dict__["_sofa_name"] = value

    def _live_array(self, name):
        return None


class Controller(_PythonComponent):
    """A Python component called by the animation loop: define onAnimateBeginEvent(event) and
    onAnimateEndEvent(event) (and onKeypressedEvent in the viewer); other events go to onEvent."""

    def reset(self):
        """Called by Sofa.Simulation.reset, after the state is back at its start."""


class _CallArrays:
    """The owner of the Data a Python force field's calls receive: numpy views of its state's
    range for the length of the call (forces writable through writeableArray(), positions not)."""

    def __init__(self, field, **arrays):
        self._field = field
        self._arrays = arrays

    def getLinkPath(self):
        return self._field.getLinkPath()

    def getPathName(self):
        return self._field.getPathName()

    def _data_value(self, name):
        return self._arrays[name]

    def _live_array(self, name):
        array = self._arrays[name]
        return array if array.flags.writeable else None

    def _set_data_value(self, name, value):
        array = self._arrays[name]
        if not array.flags.writeable:
            raise ValueError(f"{self.getPathName()}: {name} is read-only in this call")
        array[...] = value


class ForceField(_PythonComponent):
    """A force field written in Python, as SofaPython3's: addForce(mparams, f, x, v) adds the
    forces at x into f (``with f.writeableArray() as w: w[:] += ...``); addDForce(mparams, df, dx)
    adds kFactor df/dx dx (mparams["kFactor"], ["bFactor"]) for iterative solvers; addKToMatrix(mparams,
    nNodes, nDofs) returns the (nNodes nDofs)² matrix kFactor df/dx for assembling ones. Arrays are
    views of the MechanicalObject's range of the state (no copies), valid during the call."""

    def addForce(self, mparams, f, x, v):
        raise NotImplementedError(f"{self.getPathName()}: {type(self).__name__} defines no addForce")

    def addDForce(self, mparams, df, dx):
        raise NotImplementedError(f"{self.getPathName()}: {type(self).__name__} defines no addDForce")

    def addKToMatrix(self, mparams, nNodes, nDofs):
        return None

    def _fastcorot_add_force(self, mparams, f, x, v):
        arrays = _CallArrays(self, forces=f, position=x, velocity=v)
        self.addForce(mparams, Data(arrays, "forces"), Data(arrays, "position"), Data(arrays, "velocity"))

    def _fastcorot_add_dforce(self, mparams, df, dx):
        arrays = _CallArrays(self, dforce=df, dx=dx)
        self.addDForce(mparams, Data(arrays, "dforce"), Data(arrays, "dx"))
