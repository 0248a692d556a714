"""Sofa.Core.Data: one datum of a node or an object, as SofaPython3 hands it out (``obj.position``).

Its owner (a Sofa.Core.Node or object) reads and writes the value; the datum adds SofaPython3's
spellings: ``.value``, ``.array()`` (a read-only numpy view, no copy), ``writeableArray()`` /
``writeable()`` (a context manager giving a writable view), ``getLinkPath()``.
"""

import contextlib

import numpy as np


def _read_only(value):
    """A read-only numpy view of `value` (no copy where it is an array)."""
    array = np.asarray(value)
    if isinstance(value, np.ndarray):
        array = value.view()
    array.flags.writeable = False
    return array


class Data:
    """A datum `name` of `owner`. ``value`` reads and assigns it; arrays of a simulated state are views."""

    def __init__(self, owner, name):
        object.__setattr__(self, "_owner", owner)
        object.__setattr__(self, "_name", name)

    def getName(self):
        return self._name

    def getOwner(self):
        return self._owner

    def _python_owned(self):
        """Whether a script made this datum (a node's or a Python component's addData), rather than a
        component of the scene."""
        owner = self._owner
        added = getattr(owner, "_extra", {}).get("_added", ()) if hasattr(owner, "_node") else ()
        return self._name in added or self._name in getattr(owner, "__dict__", {}).get("_sofa_data", {})

    def getLinkPath(self):
        """``@/node/object.datum``: a link to this datum, for another object's attribute."""
        return self._owner.getLinkPath() + "." + self._name

    @property
    def linkpath(self):
        """SofaPython3's attribute spelling of getLinkPath()."""
        return self.getLinkPath()

    @property
    def value(self):
        """The value: a number, text, or a read-only numpy array (a view of the state for a simulated
        MechanicalObject's position, velocity and rest_position). A datum given a parent
        (setParent) reads its parent's value."""
        parent = self.getParent()
        if parent is not None:
            return parent.value
        value = self._owner._data_value(self._name)
        return _read_only(value) if isinstance(value, np.ndarray) else value

    # SofaPython3's links between data: the datum follows its parent's value.
    def _parents(self):
        return vars(self._owner).setdefault("_data_parents", {}) if hasattr(self._owner, "__dict__") else {}

    def setParent(self, parent):
        """Links this datum to `parent` (a Data, or a link path "@/node/object.datum"): reading it
        then gives the parent's value, as in SofaPython3. For a component's datum the link is also
        written into the scene (the parent's link path, or, for a datum a script made, its value),
        so that the simulation built next reads it."""
        if isinstance(parent, str):
            if not self._python_owned():
                self._owner._set_data_value(self._name, parent)
            return
        if not isinstance(parent, Data):
            raise TypeError(f"{self._where()}: setParent takes a Data or a link path, got {type(parent).__name__}")
        if parent is self or (parent._owner is self._owner and parent._name == self._name):
            raise ValueError(f"{self._where()}: setParent: a datum cannot be its own parent")
        self._parents()[self._name] = parent
        if not self._python_owned():
            self._owner._set_data_value(self._name, parent.value if parent._python_owned() else parent.getLinkPath())

    def getParent(self):
        """The Data given by setParent, or None."""
        return self._parents().get(self._name)

    def hasParent(self):
        return self.getParent() is not None

    @value.setter
    def value(self, value):
        self._owner._set_data_value(self._name, value)

    def array(self):
        """A read-only numpy view of the value (no copy: for a simulated state, its own memory)."""
        value = self._owner._data_value(self._name)
        if value is None or isinstance(value, str):
            raise TypeError(f"{self._where()}: has no array value (it is {value!r})")
        return _read_only(value)

    @contextlib.contextmanager
    def writeableArray(self):
        """A writable numpy array of the value for the `with` block: the state's own memory for a
        simulated MechanicalObject's position or velocity; otherwise a copy written back at the end."""
        live = self._owner._live_array(self._name)
        if live is not None:
            yield live
            return
        value = self._owner._data_value(self._name)
        if value is None or isinstance(value, str):
            raise TypeError(f"{self._where()}: has no array value to write into (it is {value!r})")
        array = np.array(value)
        yield array
        self.value = array

    writeable = writeableArray

    def getValueString(self):
        from fastcorot._values import to_text

        value = self._owner._data_value(self._name)
        return "" if value is None else to_text(value)

    def toList(self):
        value = self.value
        return value.tolist() if isinstance(value, np.ndarray) else value

    def _where(self):
        return f"{self._owner.getPathName()}.{self._name}"

    # numpy and sequence interplay, as SofaPython3's containers
    def __array__(self, dtype=None, copy=None):
        array = np.asarray(self._owner._data_value(self._name))
        return array.astype(dtype) if dtype is not None else array

    def __len__(self):
        value = self._owner._data_value(self._name)
        return len(value) if isinstance(value, str) else len(self.array())  # a text's length, as DataString's

    def __bool__(self):
        """A text or an array is false when empty (SofaPython3's DataString and DataContainer have a
        length); any other datum is true."""
        value = self._owner._data_value(self._name)
        if isinstance(value, (str, list, tuple, np.ndarray)):
            return len(value) > 0
        return True

    def __getitem__(self, index):
        return self.array()[index]

    def __setitem__(self, index, value):
        with self.writeableArray() as array:
            array[index] = value

    def __eq__(self, other):
        other = other.value if isinstance(other, Data) else other
        return np.array_equal(np.asarray(self.value), np.asarray(other)) if isinstance(self.value, np.ndarray) \
            else self.value == other

    __hash__ = object.__hash__

    def __setattr__(self, name, value):
        if isinstance(getattr(type(self), name, None), property):
            object.__setattr__(self, name, value)
            return
        raise AttributeError(f"{self._where()}: assign the datum's value (.value = ...) or the datum itself "
                             f"(owner.{self._name} = ...), not '{name}'")

    def __str__(self):
        return str(self.value)

    def __repr__(self):
        return f"<Sofa.Core.Data {self._where()} = {self.value!r}>"
