"""Data values of scene objects.

A value given in Python is checked against its attribute's type in the component table (the table
`fastcorot components` prints) and kept in a canonical form: float, int, bool, str, or a numpy
array (float64 for coordinates and reals, int64 for indices). Text is kept as written: it is how a
.scn file gives values, and how links (``"@grid"``, ``"@clamp.indices"``) are written. To build a
simulation, every value is handed to the compiled scene builder as text, the numbers written so that
each reads back as the same double (Python's repr), so that a scene built in Python and the same
scene read from a file give the same simulation bit for bit.
"""

import numbers
import os

import numpy as np

# Index data made of fixed-size tuples: text and flat lists read back in this shape.
TUPLE_SIZES = {"tetrahedra": 4, "edges": 2, "triangles": 3}

TEXT_TYPES = ("string", "link", "file")
TRUE_TEXTS = ("1", "true", "True", "TRUE")
FALSE_TEXTS = ("0", "false", "False", "FALSE")


def _is_bool(value):
    return isinstance(value, (bool, np.bool_))


def _number(value, label, integer):
    wanted = "an integer" if integer else "a number"
    if integer and isinstance(value, numbers.Real) and not _is_bool(value) and float(value).is_integer():
        return int(value)  # 1e4 for an integer: SOFA reads "10000.0" as 10000, as SofaPython3 writes it
    if _is_bool(value) or not isinstance(value, numbers.Integral if integer else numbers.Real):
        raise TypeError(f"{label}: expected {wanted}, got {type(value).__name__} {value!r}")
    return int(value) if integer else float(value)


def _flat(value):
    """A ragged nesting of lists, tuples and arrays of numbers as one flat list (SofaPython3 writes
    [m, V, [i0 .. i8]] into SOFA's text as its numbers in order)."""
    if isinstance(value, (list, tuple, np.ndarray)):
        return [x for item in value for x in _flat(item)]
    return [value]


def _as_array(value):
    try:
        return np.asarray(value)
    except ValueError:
        if isinstance(value, (list, tuple)):
            return np.asarray(_flat(value))  # ragged: flattened, as SofaPython3 writes it for SOFA
        raise


def _array(value, label, integer, expected):
    if _is_bool(value) or isinstance(value, (bytes, dict, set)):
        raise TypeError(f"{label}: expected {expected}, got {type(value).__name__}")
    try:
        array = _as_array(value)
    except (TypeError, ValueError) as error:
        raise TypeError(f"{label}: expected {expected}, got {type(value).__name__} ({error})") from None
    if array.dtype.kind not in ("iu" if integer else "iuf"):
        raise TypeError(f"{label}: expected {expected}, got dtype {array.dtype}")
    return array.astype(np.int64 if integer else np.float64)


def canonical(kind, name, value, where):
    """`value` for attribute `name` of type `kind` (None: a common or display attribute), checked
    and in canonical form; `where` names the object in messages. Strings are kept as written."""
    label = f"{where}: {name}"
    if isinstance(value, str):
        return value
    if isinstance(value, os.PathLike) and kind == "file":
        return os.fspath(value)
    if kind in TEXT_TYPES and _is_text_list(value):
        return " ".join(value)  # SOFA reads a list of texts as the texts separated by spaces
    if kind == "string" and name != "name" and not _is_bool(value):
        # Numbers for a text (valueType=1, an option's index; color=[1, 0, 0, 1]): SofaPython3 writes
        # them into SOFA's text, which reads them as written.
        if isinstance(value, numbers.Real):
            return to_text(value)
        if isinstance(value, (list, tuple, np.ndarray)):
            array = np.asarray(value)
            if array.size and array.dtype.kind in "iuf":
                return " ".join(to_text(v) for v in array.reshape(-1).tolist())
    if kind in TEXT_TYPES or name == "name":
        raise TypeError(f"{label}: expected a str, got {type(value).__name__} {value!r}")
    if kind == "bool":
        if isinstance(value, numbers.Integral) and not _is_bool(value) and value in (0, 1):
            return bool(value)  # SOFA reads "1" and "0" as a bool, as SofaPython3 writes an int
        if not _is_bool(value):
            raise TypeError(f"{label}: expected True or False, got {type(value).__name__} {value!r}")
        return bool(value)
    if kind in ("real", "int"):
        return _number(value, label, kind == "int")
    if kind in ("vec3", "int3"):
        array = _array(value, label, kind == "int3", "3 numbers" if kind == "vec3" else "3 integers")
        if array.size != 3:  # SofaPython3 flattens nested lists into SOFA's text: any shape of 3 values
            raise ValueError(f"{label}: expected 3 values, got shape {array.shape}")
        return array.reshape(3)
    if kind == "reals":
        array = _array(value, label, False, "a number or a list of numbers")
        return array.reshape(-1)  # nested lists are flattened, as SofaPython3 writes them for SOFA
    if kind in ("vec3s", "vec6s"):
        width = 3 if kind == "vec3s" else 6
        array = _array(value, label, False, f"an (n, {width}) array of numbers")
        if array.ndim == 1 and array.size % width == 0:
            # A flat list, as SofaPython3 passes it to SOFA (its numbers read in groups of `width`).
            array = array.reshape(-1, width)
        if array.ndim != 2 or array.shape[1] != width:
            raise ValueError(f"{label}: expected an (n, {width}) array of numbers, got shape {array.shape}")
        return array
    if kind == "indices":
        array = _array(value, label, True, "integer indices")
        if array.ndim == 0:
            array = array.reshape(1)
        size = TUPLE_SIZES.get(name)
        if size and not (array.ndim == 2 and array.shape[1] == size) and not (array.ndim == 1 and array.size % size == 0):
            raise ValueError(f"{label}: expected an (m, {size}) array of indices, got shape {array.shape}")
        if size and array.ndim == 1:
            array = array.reshape(-1, size)
        if array.size and array.min() < 0:
            raise ValueError(f"{label}: index {array.min()} is negative")
        return array
    # Common and display attributes, and those of ignored components: any plain value.
    if _is_bool(value) or isinstance(value, numbers.Real):
        return value
    if _is_text_list(value):
        return " ".join(value)
    return _as_array(value)


def _is_text_list(value):
    return isinstance(value, (list, tuple)) and len(value) > 0 and all(isinstance(v, str) for v in value)


def to_text(value):
    """The value as a scene file writes it."""
    if isinstance(value, str):
        return value
    if _is_bool(value):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        return repr(float(value))
    array = _as_array(value).reshape(-1)
    if array.dtype.kind == "b":
        return " ".join("true" if v else "false" for v in array.tolist())
    if array.dtype.kind in "iu":
        return " ".join(str(v) for v in array.tolist())
    return " ".join(repr(float(v)) for v in array.tolist())


def from_text(kind, name, text, where):
    """The canonical value of text as written in a scene (links and text types stay text).
    Raises ValueError naming the object and the attribute when the text does not fit the type."""
    if kind in TEXT_TYPES or kind is None or text.startswith("@"):
        return text
    label = f'{where}: {name} = "{text}"'
    if kind == "bool":
        if text in TRUE_TEXTS or text in FALSE_TEXTS:
            return text in TRUE_TEXTS
        raise ValueError(f"{label}: expected true/false or 1/0")
    tokens = text.replace(",", " ").replace("[", " ").replace("]", " ").split()
    values = []
    for token in tokens:
        try:
            number = float(token)
        except ValueError:
            number = float("nan")
        if not np.isfinite(number) or "_" in token:
            raise ValueError(f"{label}: '{token}' is not a finite number")
        values.append(number)
    integer = kind in ("int", "int3", "indices")
    if integer and any(not v.is_integer() for v in values):
        raise ValueError(f"{label}: expected integers")
    array = np.array(values, dtype=np.int64 if integer else np.float64)
    if kind in ("real", "int"):
        if array.size != 1:
            raise ValueError(f"{label}: needs one number, got {array.size}")
        return array[0].item()
    if kind in ("vec3s", "vec6s"):
        width = 3 if kind == "vec3s" else 6
        if array.size % width != 0:
            raise ValueError(f"{label}: needs {width} numbers per {'point' if width == 3 else 'pair'}, got {array.size} numbers")
        array = array.reshape(-1, width)
    return canonical(kind, name, array, where)
