"""Scenes in SofaPython3's shape: a tree of nodes holding objects (SOFA components) and their data.

    root = fastcorot.Node("root", dt=0.01, gravity=[0, -9.81, 0])
    beam = root.add_child("beam")
    beam.add_object("MechanicalObject", name="dofs", position=points)
    root = fastcorot.load("scene.scn")

The tree is a description, exactly what a .scn file holds: `fastcorot.Simulation(root)` hands it
to the same scene builder as `fastcorot run`. Every object remembers where it was made (the
Python file and line of its add_object, or its place in the .scn file), and errors name that
place, as the command line's do. Relative file names (a mesh loader's `filename`) are relative to
the folder of that file, as in a .scn file.

Once a Simulation is built from a root, the simulated MechanicalObjects' `position` and
`velocity` are numpy arrays viewing the simulation's state (writing into them, or assigning them,
changes the state), `rest_position` is a read-only view that assigning replaces (SOFA's
RestShapeSpringsForceField follows it; the other fields keep the rest shape of init, as in SOFA),
and the root's `dt` and `gravity` are the simulation's. Other data stay the description: a change takes effect in the next Simulation built
from the tree (as SOFA applies most changes at the next init).
"""

import functools
import os
import sys
import warnings

import numpy as np

from . import _core
from ._values import canonical, from_text, to_text

_PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))
_STATE_VIEWS = ("position", "velocity", "rest_position")
# Outputs of a simulated TetrahedronFEMForceField (numpy copies, after the last step).
_VON_MISES = ("vonMisesPerNode", "vonMisesPerElement")
# Data of a simulated BilateralLagrangianConstraint that scripts change between steps.
_BILATERAL_LIVE = ("rest_vector", "activate", "load")
_NOT_LIVE = object()  # a constraint datum the running simulation does not hold
_FORCE_FIELDS = ("FastTetrahedralCorotationalForceField", "TetrahedronFEMForceField")


# Folders whose frames are not "the caller": this package's, and those of front ends built on it
# (the Sofa compatibility package adds its own).
INTERNAL_FOLDERS = {_PACKAGE_DIR}


class SceneWarning(UserWarning):
    """An attribute a component does not have (ignored, as SOFA ignores it), with the closest name."""


def _caller_location():
    """(file, line) of the first caller outside this package (and the front ends on it)."""
    frame = sys._getframe(1)
    while frame is not None and os.path.dirname(os.path.abspath(frame.f_code.co_filename)) in INTERNAL_FOLDERS:
        frame = frame.f_back
    return (frame.f_code.co_filename, frame.f_lineno) if frame is not None else ("<python>", 0)


@functools.lru_cache(maxsize=None)
def _spec(type_name):
    """The component table's entry for a type: (canonical name, {attribute: (type, default, doc)}, doc)."""
    spec = _core.component_spec(type_name)
    if spec is None:
        return None
    attributes = {name: (kind, default, doc) for name, kind, default, doc in spec["attributes"]}
    return spec["name"], attributes, spec["doc"]


class Object:
    """One component of a node: its type (e.g. "MechanicalObject") and its data, read and written
    by name as attributes (``obj.youngModulus``) or items (``obj["youngModulus"]``). Made by
    Node.add_object or fastcorot.load. ``help_text()`` lists its data with their meaning."""

    def __init__(self, node, type_name, attributes, location, check=True, strict=True):
        object.__setattr__(self, "_node", node)
        object.__setattr__(self, "_type", type_name)
        object.__setattr__(self, "_location", location)
        object.__setattr__(self, "_data", {})
        object.__setattr__(self, "_binding", None)  # (SimulationCore, object index) once simulated
        object.__setattr__(self, "_mapped", None)  # (SimulationCore, state key): a mapped state once simulated
        # (SimulationCore, index): a Lagrangian constraint once simulated (index None: the constraint solver)
        object.__setattr__(self, "_lagrangian", None)
        object.__setattr__(self, "_strict", strict)  # False: unknown attributes are warnings, as SOFA's
        if check:
            self._check(list(attributes))
        for name, value in attributes.items():
            self._data[name] = value if not check else self._canonical(name, value)

    # --- what it is -------------------------------------------------------------------------
    @property
    def type(self):
        """The component type as written (an alias such as FixedConstraint stays as given)."""
        return self._type

    @property
    def node(self):
        return self._node

    @property
    def location(self):
        """Where the object was made: "file:line"."""
        return f"{self._location[0]}:{self._location[1]}"

    def _label(self):
        name = self._data.get("name")
        return f"{self._type} '{name}'" if isinstance(name, str) and name else self._type

    def _check(self, names):
        _, warned = _core.check_object(self._type, names, *self._location, self._strict)
        for line in warned:
            warnings.warn(line, SceneWarning, stacklevel=4)

    def _kind(self, name):
        if self._type == "BilateralLagrangianConstraint" and name == "rest_vector" and self._rigid_pair():
            return "vec6s"  # SOFA's Rigid3 variant: 6 numbers per pair (offset, rotation)
        spec = _spec(self._type)
        if spec and name in spec[1]:
            return spec[1][name][0]
        return None

    def _rigid_pair(self):
        """A Rigid3 pair constraint: by its template, or by what the running constraint holds."""
        template = self._data.get("template")
        if isinstance(template, str) and template.startswith("Rigid"):
            return True
        if self._lagrangian is not None and self._lagrangian[1] is not None:
            core, index = self._lagrangian
            return core.bilateral(index)["rest_vector"].shape[1] == 6
        return False

    def data_names(self):
        """The data this object has: those given, then the others its component supports."""
        names = list(self._data)
        spec = _spec(self._type)
        if spec:
            names += [name for name in spec[1] if name not in self._data]
        return names

    def help_text(self):
        """The component's description and its data (type, default, meaning), from the table that
        `fastcorot components` prints."""
        spec = _spec(self._type)
        if spec is None:
            return f"{self._type}: accepted without effect on the mechanics"
        lines = [f"{spec[0]}: {spec[2]}"]
        for name, (kind, default, doc) in spec[1].items():
            lines.append(f"  {name} ({kind}, default {default or '-'}): {doc}")
        return "\n".join(lines)

    def link(self, data=None):
        """The link to this object (``"@/beam/clamp"``) or to one of its data (``"@/beam/clamp.indices"``),
        for another object's attribute."""
        name = self._data.get("name")
        if not isinstance(name, str) or not name:
            raise ValueError(f"{self.location}: {self._type}: an object needs a name to be linked to")
        # From the root, its name included: SOFA drops a leading root name, so the link holds even
        # when a child has the root's name.
        text = "@/" + self._node.path + "/" + name
        return text + ("." + data if data else "")

    # --- data -----------------------------------------------------------------------------------
    def _canonical(self, name, value):
        if name in _STATE_VIEWS and self._is_rigid_or_vec12() and not isinstance(value, str):
            # Rigid3 rows (7 or 6 numbers each), Vec1 and Vec2 rows are kept as SOFA's text: flat numbers.
            return to_text(np.asarray(value, dtype=float).reshape(-1))
        kind = self._kind(name)
        if (kind == "vec3s" and self._type == "BilateralLagrangianConstraint" and name == "rest_vector"
                and np.ndim(value) == 2 and np.shape(value)[1] == 6):
            kind = "vec6s"  # rows of a Rigid3 pair, before the linked states tell the template
        if isinstance(value, Object) and kind == "link":
            value = value.link()
        return canonical(kind, name, value, f"{self.location}: {self._label()}")

    def _is_rigid_or_vec12(self):
        template = self._data.get("template")
        return self._is_rigid() or (isinstance(template, str) and template.startswith(("Vec1", "Vec2")))

    def _state_width(self, name):
        """Numbers per row of state vector `name`: Rigid3 7 (velocities 6), Vec1 1, Vec2 2."""
        if self._is_rigid():
            return 6 if name == "velocity" else 7
        return int(self._data["template"][3])

    def _is_rigid(self):
        template = self._data.get("template")
        return isinstance(template, str) and template.startswith("Rigid")

    def _read_lagrangian(self, name):
        """What the running constraint stage holds for `name`, or _NOT_LIVE."""
        core, index = self._lagrangian
        if index is None:
            if name == "constraintForces":
                return core.constraint_forces()
            report = core.constraint_report()
            live = {"currentIterations": report["iterations"], "currentError": report["error"],
                    "currentNumConstraints": report["rows"]}
            return live.get(name, _NOT_LIVE)
        if name in core.constraint_live(index):  # what the constraint keeps of its own (CableConstraint's outputs)
            values = core.read_constraint(index, name)
            kind = self._kind(name)
            if kind == "real":
                return float(values[0])
            if kind == "int":
                return int(values[0])
            return values
        if self._type == "BilateralLagrangianConstraint" and name in _BILATERAL_LIVE:
            if name != "rest_vector" and self._rigid_pair():
                return _NOT_LIVE  # kept as written: SOFA's Rigid3 variant reads neither
            return core.bilateral(index)[name]
        return _NOT_LIVE

    def _read(self, name):
        if self._lagrangian is not None:
            value = self._read_lagrangian(name)
            if value is not _NOT_LIVE:
                return value
        if self._binding is not None and name in _STATE_VIEWS:
            core, k, start, stop = self._binding
            if self._is_rigid():
                # Rigid3: (n, 7) x y z qx qy qz qw (a copy: the orientations live beside the state);
                # velocities (n, 6) v ω, a view of the state's two blocks per rigid.
                if name == "velocity":
                    return core.velocity(k)[start:stop].reshape(-1, 6)
                return core.rigid_rest_position(k, start, stop) if name == "rest_position" else core.rigid_position(k, start, stop)
            return getattr(core, name)(k)[start:stop]
        if self._mapped is not None and name in ("position", "velocity"):
            # A mapped MechanicalObject: what its mapping gives at the current step (a copy).
            core, key = self._mapped
            array = core.states()[key][name]
            array.flags.writeable = False
            return array
        if self._binding is not None and name in _VON_MISES:
            core, k = self._binding[:2]
            return core.von_mises_stress(k, name == "vonMisesPerNode")
        kind = self._kind(name)
        where = f"{self.location}: {self._label()}"
        if name in _STATE_VIEWS and self._is_rigid_or_vec12() and name in self._data:
            value = self._data[name]
            if isinstance(value, str) and value.startswith("@"):
                return value
            array = from_text("reals", name, value, where) if isinstance(value, str) else np.asarray(value, dtype=float)
            width = self._state_width(name)
            if array.size % width:
                raise ValueError(f"{where}: {name} has {array.size} numbers: {width} per "
                                 f"{'rigid' if self._is_rigid() else 'point'} are needed")
            return array.reshape(-1, width)
        if name in self._data:
            value = self._data[name]
            return from_text(kind, name, value, where) if isinstance(value, str) else value
        spec = _spec(self._type)
        if spec and name in spec[1]:
            default = spec[1][name][1]
            if not default:
                return None
            try:
                return from_text(kind, name, default, where)
            except ValueError:
                return None  # a default that is a rule rather than a value (velocity "0": zero everywhere)
        if _core.is_common_attribute(name):
            return None
        raise AttributeError(f"{where} has no data '{name}'; its data: {', '.join(self.data_names())}")

    def _write(self, name, value):
        if self._lagrangian is not None and self._lagrangian[1] is not None:
            core, index = self._lagrangian
            if name in core.constraint_live(index):
                self._check([name])
                canonical = self._canonical(name, value)
                live = from_text(self._kind(name), name, canonical, self.location) if isinstance(canonical, str) else canonical
                try:
                    core.write_constraint(index, name, np.asarray(live, dtype=float).reshape(-1).tolist())
                except ValueError as error:
                    raise ValueError(f"{self.location}: {self._label()}: {error}") from None
                self._data[name] = canonical
                return
        if self._lagrangian is not None and self._type == "BilateralLagrangianConstraint" and name in _BILATERAL_LIVE:
            core, index = self._lagrangian
            self._check([name])
            canonical = self._canonical(name, value)
            live = from_text(self._kind(name), name, canonical, self.location) if isinstance(canonical, str) else canonical
            try:
                width = 6 if self._rigid_pair() else 3
                core.set_bilateral(index, **{name: np.asarray(live, dtype=float).reshape(-1, width) if name == "rest_vector" else live})
            except ValueError as error:
                raise ValueError(f"{self.location}: {self._label()}: {error}") from None
            self._data[name] = canonical
            return
        if self._lagrangian is not None and self._type == "StopperLagrangianConstraint" and name in ("min", "max"):
            core, index = self._lagrangian
            self._check([name])
            canonical = self._canonical(name, value)
            live = from_text(self._kind(name), name, canonical, self.location) if isinstance(canonical, str) else canonical
            try:
                core.set_stopper(index, **{name: float(np.asarray(live, dtype=float).reshape(-1)[0])})
            except (ValueError, TypeError) as error:
                raise ValueError(f"{self.location}: {self._label()}: {error}") from None
            self._data[name] = canonical
            return
        if self._binding is not None and name in _STATE_VIEWS:
            core, k, start, stop = self._binding
            if name == "rest_position":
                # SOFA's RestShapeSpringsForceField reads the rest positions at every step and follows;
                # the other fields keep the rest shape they took at init, as SOFA's do.
                try:
                    if self._is_rigid():
                        core.set_rigid_rest_position(k, np.asarray(value, dtype=float).reshape(-1), start, stop)
                    else:
                        core.set_rest_position(k, np.asarray(value, dtype=float).reshape(-1, 3), start, stop)
                except (ValueError, IndexError) as error:
                    raise ValueError(f"{self.location}: {self._label()}: {error}") from None
                return
            if self._is_rigid():
                if name == "position":
                    try:
                        core.set_rigid_position(k, np.asarray(value, dtype=float).reshape(-1), start, stop)
                    except ValueError as error:
                        raise ValueError(f"{self.location}: {self._label()}: {error}") from None
                else:
                    core.set_velocity(k, np.asarray(value, dtype=float).reshape(-1, 3), start, stop)
                return
            getattr(core, "set_" + name)(k, value, start, stop)
            return
        self._check([name])
        self._data[name] = self._canonical(name, value)

    # --- cutting (force fields of a built Simulation) ------------------------------------------
    def _simulated_topology(self, what):
        if self._type not in _FORCE_FIELDS:
            raise TypeError(f"{self.location}: {self._label()}: {what} is for a "
                            "FastTetrahedralCorotationalForceField or TetrahedronFEMForceField")
        if self._binding is None:
            raise RuntimeError(f"{self.location}: {self._label()}: {what} needs a built "
                               "fastcorot.Simulation of its scene")
        return self._binding

    def remove_tetrahedra(self, indices):
        """Cuts: removes tetrahedra (indices as currently numbered) from this force field's
        topology in the running Simulation; the force fields and the mass on it follow. SOFA's
        swap-with-last renumbering: returns the new index of every old tetrahedron (-1 when
        removed). Points stay (those left without tetrahedra and mass are held still)."""
        core, k = self._simulated_topology("remove_tetrahedra")[:2]
        return core.remove_tetrahedra(k, indices)

    def add_tetrahedra(self, tetrahedra):
        """Appends (m, 4) tetrahedra over existing points to this force field's topology in the
        running Simulation (rest data from the rest positions)."""
        core, k = self._simulated_topology("add_tetrahedra")[:2]
        core.add_tetrahedra(k, tetrahedra)

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        return self._read(name)

    def __setattr__(self, name, value):
        if name.startswith("_") or isinstance(getattr(type(self), name, None), property):
            object.__setattr__(self, name, value)
        else:
            self._write(name, value)

    def __getitem__(self, name):
        return self._read(name)

    def __setitem__(self, name, value):
        self._write(name, value)

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self.data_names()))

    def __repr__(self):
        return f"<{self._label()} in {self._node.path} ({self.location})>"

    def _text_attributes(self):
        return {name: to_text(value) for name, value in self._data.items()}


class Node:
    """A node of the scene tree: a name, data (``dt``, ``gravity``; only the root's count), objects
    and child nodes. ``node.beam`` and ``node["beam"]`` give the child or object of that name;
    ``node["beam/dofs"]`` walks a path."""

    def __init__(self, name="root", **data):
        if not isinstance(name, str):
            raise TypeError(f"Node: name must be a str, got {type(name).__name__}")
        object.__setattr__(self, "_name", name)
        object.__setattr__(self, "_data", {})  # node attributes other than name
        object.__setattr__(self, "_objects", [])
        object.__setattr__(self, "_children", [])
        object.__setattr__(self, "_parent", None)
        object.__setattr__(self, "_location", _caller_location())
        object.__setattr__(self, "_core", None)  # the SimulationCore built from this node as root
        for key, value in data.items():
            setattr(self, key, value)

    # --- the tree -------------------------------------------------------------------------------
    @property
    def name(self):
        return self._name

    @name.setter
    def name(self, value):
        if not isinstance(value, str):
            raise TypeError(f"Node '{self._name}': name must be a str, got {type(value).__name__}")
        object.__setattr__(self, "_name", value)

    @property
    def parent(self):
        return self._parent

    @property
    def children(self):
        return tuple(self._children)

    @property
    def objects(self):
        return tuple(self._objects)

    @property
    def location(self):
        return f"{self._location[0]}:{self._location[1]}"

    def _lineage(self):
        nodes = [self]
        while nodes[0]._parent is not None:
            nodes.insert(0, nodes[0]._parent)
        return nodes

    @property
    def path(self):
        """Node names from the root joined by '/', as the command line's state dumps name objects."""
        return "/".join(n._name for n in self._lineage())

    def add_child(self, name, **data):
        """A new child node (``data``: dt, gravity, activated)."""
        child = Node(name, **data)
        object.__setattr__(child, "_location", _caller_location())
        object.__setattr__(child, "_parent", self)
        self._children.append(child)
        return child

    def add_object(self, type_name, /, **attributes):
        """A new object of a SOFA component type with its data, checked against the component
        table: an unknown type or attribute is a ValueError with the scene loader's message; a
        value of the wrong type a TypeError, of the wrong shape a ValueError."""
        obj = Object(self, type_name, attributes, _caller_location())
        self._objects.append(obj)
        return obj

    addChild = add_child  # SofaPython3's spellings
    addObject = add_object

    # --- data -----------------------------------------------------------------------------------
    def _node_data(self, name, kind, default):
        value = self._data.get(name)
        if value is None:
            return default
        return from_text(kind, name, value, f"{self.location}: Node '{self._name}'") if isinstance(value, str) else value

    @property
    def dt(self):
        """The time step (only the root's counts; SOFA's default 0.01)."""
        if self._core is not None:
            return self._core.dt
        return self._node_data("dt", "real", _core.DEFAULT_DT)

    @dt.setter
    def dt(self, value):
        value = canonical("real", "dt", value, f"Node '{self._name}'")
        if isinstance(value, str):
            value = from_text("real", "dt", value, f"Node '{self._name}'")
        if not (np.isfinite(value) and value > 0):
            raise ValueError(f"Node '{self._name}': dt = {value!r}: must be a finite number > 0")
        if self._core is not None:
            self._core.dt = value
        self._data["dt"] = value

    @property
    def gravity(self):
        """Gravity (only the root's counts; SOFA's default (0, -9.81, 0))."""
        if self._core is not None:
            return np.array(self._core.gravity)
        return self._node_data("gravity", "vec3", np.array(_core.DEFAULT_GRAVITY))

    @gravity.setter
    def gravity(self, value):
        value = canonical("vec3", "gravity", value, f"Node '{self._name}'")
        if isinstance(value, str):
            value = from_text("vec3", "gravity", value, f"Node '{self._name}'")
        if not np.all(np.isfinite(value)):
            raise ValueError(f"Node '{self._name}': gravity = {value!r}: expected 3 finite numbers")
        if self._core is not None:
            self._core.gravity = value
        self._data["gravity"] = value

    @property
    def activated(self):
        """Whether SOFA's visitors enter the node (default True). A deactivated node's subtree is
        not simulated, collided or drawn; links into it still read its objects' data."""
        return self._node_data("activated", "bool", True)

    @activated.setter
    def activated(self, value):
        self._data["activated"] = canonical("bool", "activated", value, f"Node '{self._name}'")

    @property
    def attributes(self):
        """The node's attributes as a scene file writes them (name included)."""
        return {"name": self._name, **{key: to_text(value) for key, value in self._data.items()}}

    # --- lookup -----------------------------------------------------------------------------------
    def _find(self, name):
        for child in self._children:
            if child._name == name:
                return child
        for obj in self._objects:
            if obj._data.get("name") == name:
                return obj
        for child in getattr(self, "_alias_children", ()):  # moved below a second parent (Sofa's addChild)
            if child._name == name and child._parent is not self:
                return child
        return None

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        found = self._find(name)
        if found is None:
            names = [c._name for c in self._children] + [o._data["name"] for o in self._objects if "name" in o._data]
            raise AttributeError(f"Node '{self.path}' has no child or object named '{name}'"
                                 f"{'; it has: ' + ', '.join(map(str, names)) if names else ''}")
        return found

    def __setattr__(self, name, value):
        if name.startswith("_") or isinstance(getattr(type(self), name, None), property):
            object.__setattr__(self, name, value)
        else:
            raise AttributeError(f"Node '{self._name}' has no data '{name}' (a node's data are name, dt, "
                                 "gravity and activated; add objects with add_object and children with add_child)")

    def __getitem__(self, path):
        found = self
        for part in path.split("/"):
            found = found._find(part) if isinstance(found, Node) else None
            if found is None:
                raise KeyError(f"Node '{self.path}': nothing at '{path}' (stopped at '{part}')")
        return found

    def __repr__(self):
        return f"<Node {self.path}: {len(self._objects)} objects, {len(self._children)} children>"

    # --- to and from the compiled scene graph ------------------------------------------------------
    def _tree(self, objects):
        """The tree the scene builder takes; appends this subtree's objects to `objects` in
        document order (a node's objects, then its children's), the order the builder ranks them in."""
        objects.extend(self._objects)
        items = [(obj._type, obj._text_attributes(), *obj._location) for obj in self._objects]
        children = [child._tree(objects) for child in self._children]
        return (self._name, self.attributes, items, children, *self._location)


def _node_from_tree(tree, parent):
    name, attributes, objects, children, file, line = tree
    node = Node.__new__(Node)
    for key, value in (("_name", name), ("_objects", []), ("_children", []), ("_parent", parent),
                       ("_location", (file, line)), ("_core", None)):
        object.__setattr__(node, key, value)
    object.__setattr__(node, "_data", {k: v for k, v in attributes.items() if k != "name"})
    for type_name, values, object_file, object_line in objects:
        node._objects.append(Object(node, type_name, values, (object_file, object_line), check=False))
    for child in children:
        node._children.append(_node_from_tree(child, node))
    return node


def load(path):
    """The root node of a SOFA scene file (.scn; includes expanded). Its objects keep their file
    and line, so errors read as `fastcorot run`'s. A missing file raises FileNotFoundError, a
    malformed one or an unknown component or attribute ValueError."""
    root = _node_from_tree(_core.parse_scene_file(os.fspath(path)), None)
    pending = [root]
    while pending:
        node = pending.pop()
        for obj in node._objects:
            _core.check_object(obj._type, list(obj._data), *obj._location)
        pending.extend(node._children)
    return root


def walk(node):
    """The node and its descendants, depth first."""
    yield node
    for child in node._children:
        yield from walk(child)


__all__ = ["Node", "Object", "SceneWarning", "load", "walk"]
