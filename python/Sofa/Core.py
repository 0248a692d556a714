"""Sofa.Core: SofaPython3's scene graph (Node, objects, Data, Controller) over fastcorot's scene tree.

A Sofa.Core.Node wraps a fastcorot.Node (``node.fastcorot_node``) and an object wraps a
fastcorot.Object: addChild / addObject build the same tree `fastcorot run` builds from a .scn file,
so a script and its XML transcription simulate bit for bit the same. What differs from SofaPython3:
an attribute of a node or object is a Data (``.value``), as there; numbers go to the scene builder
as the same doubles as in a .scn file; unknown attributes warn with the closest name (SceneWarning);
an unknown component is a ValueError naming it and the script line.
"""

import difflib
import os
import warnings

import numpy as np

import fastcorot
from fastcorot import _core
from fastcorot import scene as _scene
from fastcorot._values import TUPLE_SIZES as _TUPLE_SIZES
from fastcorot._values import to_text

from ._components import Controller, ForceField, _PythonComponent
from ._data import Data
from ._matrices import object_methods

_scene.INTERNAL_FOLDERS.add(os.path.dirname(os.path.abspath(__file__)))

# SOFA's outputs of loaders, engines and topologies that scripts link to before the scene is built.
_OUTPUTS = frozenset({
    "position", "positions", "edges", "triangles", "quads", "tetrahedra", "tetras", "hexahedra", "normals",
    "indices", "pointIndices", "pointsInROI", "edgesInROI", "trianglesInROI", "quadsInROI", "tetrahedraInROI", "hexahedraInROI",
    "edgeIndices", "triangleIndices", "quadIndices", "tetrahedronIndices", "hexahedronIndices", "nbIndices",
    "indicesOut", "volume", "output_position", "outputPoints", "outputTetrahedra", "outputTriangles"})

# How outputs and linked data read as numpy values: (int or float, row width; 0 for one number,
# None for a flat array).
_OUTPUT_SHAPES = {
    "position": (float, 3), "positions": (float, 3), "normals": (float, 3), "pointsInROI": (float, 3),
    "pointsOutROI": (float, 3), "output_position": (float, 3), "outputPoints": (float, 3),
    "edges": (int, 2), "triangles": (int, 3), "quads": (int, 4), "tetrahedra": (int, 4), "tetras": (int, 4),
    "hexahedra": (int, 8), "hexas": (int, 8), "edgesInROI": (int, 2), "trianglesInROI": (int, 3), "quadsInROI": (int, 4),
    "tetrahedraInROI": (int, 4), "hexahedraInROI": (int, 8), "outputTetrahedra": (int, 4), "outputTriangles": (int, 3),
    "indices": (int, None), "pointIndices": (int, None), "indicesOut": (int, None), "edgeIndices": (int, None),
    "triangleIndices": (int, None), "quadIndices": (int, None), "tetrahedronIndices": (int, None),
    "hexahedronIndices": (int, None), "nbIndices": (int, 0), "volume": (float, 0)}
_KIND_SHAPES = {"vec3s": (float, 3), "vec6s": (float, 6), "reals": (float, None), "real": (float, 0), "int": (int, 0),
                "vec3": (float, None), "int3": (int, None)}


def _shape_of(kind, name):
    """(int or float, width) of a datum read as numbers, None for text."""
    if kind == "indices":
        size = _TUPLE_SIZES.get(name) or _OUTPUT_SHAPES.get(name, (int, None))[1]
        return (int, size) if size else (int, None)
    if kind in _KIND_SHAPES:
        return _KIND_SHAPES[kind]
    return _OUTPUT_SHAPES.get(name) if kind is None else None


# A node's own data (SOFA's Node and its context); only dt and gravity change the mechanics.
_NODE_DATA = ("name", "dt", "gravity", "time", "bbox", "animate", "activated", "multiThreadSimulation")


def _closest(name, names):
    match = difflib.get_close_matches(name, list(names), n=1)
    return f" (did you mean '{match[0]}'?)" if match else ""


def _value_for_scene(value):
    """A keyword value of addObject as the scene tree takes it: links for Data, objects and nodes; a
    datum a script added (a prefab's parameter, a controller's addData) gives its value (the scene
    builder reads the components' data only)."""
    if isinstance(value, Data) and value._python_owned():
        return _value_for_scene(value.value)
    if isinstance(value, (Data, BaseObject, Node)):
        return value.getLinkPath()
    if isinstance(value, (list, tuple)):
        return [_nested_value(item) for item in value]
    return value


def _nested_value(item):
    """An item of a list given to addObject: a Data there stands for its value, as SofaPython3
    writes it into SOFA's text (`position=[[self.angleIn]]`)."""
    if isinstance(item, Data):
        try:
            return _nested_value(item.value)
        except AttributeError:  # an output computed as the scene is built: its link
            return item.getLinkPath()
    if isinstance(item, (list, tuple)):
        return [_nested_value(x) for x in item]
    return item


def _graft_links(top):
    """`top`, a tree built apart (a prefab made before being added), now hangs below another node:
    the links its objects hold to objects of its own, absolute while `top` was a root ("@/loader"),
    are written from the new root ("@/finger/loader"). SOFA resolves such links as the objects are
    created, so that they keep pointing at the same objects wherever the tree is added."""
    prefix = "/" + "/".join(n.name for n in top._lineage()[1:])

    def inside(path):  # whether "/a/b.data" names a node or an object of `top`'s tree
        node = top
        parts = path.lstrip("/").split(".", 1)[0].split("/")
        for k, part in enumerate(parts):
            child = next((c for c in node._children if c.name == part), None)
            if child is not None:
                node = child
            elif k == len(parts) - 1:
                return any(o._data.get("name") == part for o in node._objects)
            else:
                return False
        return True

    _rewrite_links(top, lambda w: "@" + prefix + w[1:] if inside(w[1:]) else w)


def _rewrite_links(top, moved):
    """Each absolute link word ("@/a/b.data") in the data of `top`'s tree replaced by moved(word)."""
    stack = [top]
    while stack:
        node = stack.pop()
        stack.extend(node._children)
        for obj in node._objects:
            for key, value in list(obj._data.items()):
                if isinstance(value, str) and "@/" in value:
                    obj._data[key] = " ".join(moved(w) if w.startswith("@/") else w for w in value.split(" "))


def _add_parent(child, parent):
    """SOFA's graph lets a node have several parents: STLIB's Scene hangs its Modelling node under
    Simulation too (whose solvers then integrate it), Rigidify its object under the two mapped nodes
    that feed its SubsetMultiMapping. fastcorot's tree has one parent per node: the node moves under
    the last parent it is added to, and stays found by name from the earlier ones (node.Modelling);
    the links written to it through its old path are rewritten to the new one."""
    if any(node is child for node in parent._lineage()):
        raise ValueError(f"addChild: node '{child.name}' is '{parent.name}' or above it: the graph would have a cycle")
    old_root = child._lineage()[0]
    old_path = "/" + "/".join(n.name for n in child._lineage()[1:])
    old_parent = child._parent
    old_parent._children.remove(child)
    aliases = getattr(old_parent, "_alias_children", None)
    if aliases is None:
        aliases = []
        object.__setattr__(old_parent, "_alias_children", aliases)
    aliases.append(child)
    object.__setattr__(child, "_parent", parent)
    parent._children.append(child)
    new_path = "/" + "/".join(n.name for n in child._lineage()[1:])
    root_name = "/" + old_root.name

    def moved(word):
        for prefix in (old_path, root_name + old_path):  # SOFA's "@/Modelling/x", fastcorot's "@/root/Modelling/x"
            rest = word[1 + len(prefix):]
            if word.startswith("@" + prefix) and (rest == "" or rest[0] in "/."):
                return "@" + new_path + rest
        return word

    for root in {id(old_root): old_root, id(child._lineage()[0]): child._lineage()[0]}.values():
        _rewrite_links(root, moved)


class _NamedList(list):
    """A node's children or objects, as SofaPython3's NodeIterator: a list that also takes names
    (``"solver" in node.objects``, ``node.children["Visual"]``)."""

    def _named(self, name):
        return next((item for item in self if item.getName() == name), None)

    def __contains__(self, item):
        if isinstance(item, str):
            return self._named(item) is not None
        return list.__contains__(self, item)

    def __getitem__(self, index):
        if isinstance(index, str):
            found = self._named(index)
            if found is None:
                raise KeyError(f"no item named '{index}'")
            return found
        return list.__getitem__(self, index)

    def at(self, index):
        return list.__getitem__(self, index)


class BaseObject:
    """An object of a node (a SOFA component): its data are attributes (``obj.youngModulus.value``)."""

    def __init__(self, wrapped, context):
        object.__setattr__(self, "_object", wrapped)
        object.__setattr__(self, "_context", context)
        object.__setattr__(wrapped, "_sofa", self)

    @staticmethod
    def _of(wrapped, context):
        existing = getattr(wrapped, "_sofa", None)
        return existing if existing is not None else BaseObject(wrapped, context)

    @property
    def fastcorot_object(self):
        """The fastcorot.Object this wraps."""
        return self._object

    def getName(self):
        name = self._object._data.get("name")
        return name if isinstance(name, str) and name else self._object.type

    def getClassName(self):
        return self._object.type

    def getTemplateName(self):
        template = self._object._data.get("template")
        return template if isinstance(template, str) else ""

    def getContext(self):
        return self._context

    def getPathName(self):
        return self._context._sofa_path(self.getName())

    def getLinkPath(self):
        return "@" + self.getPathName()

    def getDataFields(self):
        return [Data(self, name) for name in self._object.data_names()]

    def getData(self, name):
        return Data(self, name) if self._has_data(name) else None

    findData = getData

    def init(self):
        """Accepted: objects are initialised when the simulation is built (Sofa.Simulation.init)."""

    reinit = init

    def _has_data(self, name):
        return name in self._object.data_names() or _core.is_common_attribute(name) or self._is_output(name)

    def _is_output(self, name):
        """Whether `name` is one of SOFA's outputs of this loader, engine or topology (a loader's
        position, a BoxROI's indices): computed as the scene is built, so given to other components
        as a link (``roi.indices.getLinkPath()``)."""
        if name in self._object._data or name not in _OUTPUTS:
            return False
        spec = _core.component_spec(self._object.type)
        return spec is not None and spec["category"] in ("loader", "surfaceloader", "engine", "topology", "trianglecontainer")

    # the owner protocol of Data
    def _data_value(self, name):
        if self._is_output(name) and name not in self._object.data_names():
            return self._evaluated(name)  # a loader's or engine's output: computed now, as SofaPython3 has it
        value = self._object._read(name)
        if isinstance(value, str) and value.startswith("@") and _shape_of(self._object._kind(name), name) is not None:
            return self._evaluated(name)  # a link: the value it brings, as SofaPython3 reads it
        return value

    def _evaluated(self, name):
        """Data `name` as the scene builder reads it from the tree as it is now (links followed, files
        loaded, engines computed). What cannot be read yet (a missing file, a link to an object not
        added yet) is warned and read as empty, as SOFA logs it and leaves the data empty."""
        root = self._object._node._lineage()[0]
        objects = []
        tree = root._tree(objects)
        index = next(i for i, o in enumerate(objects) if o is self._object)
        shape = _shape_of(self._object._kind(name), name) or (float, None)
        try:
            numbers = _core.scene_data_value(tree, index, name)
        except ValueError as error:
            warnings.warn(f"{self.getPathName()}.{name}: {error}", _scene.SceneWarning, stacklevel=4)
            numbers = []
        kind, width = shape
        if kind is float and width == 0:
            return float(numbers[0]) if numbers else 0.0
        if kind is int and width == 0:
            return int(numbers[0]) if numbers else 0
        array = np.asarray(numbers, dtype=np.int64 if kind is int else np.float64)
        return array.reshape(-1, width) if width else array

    def _set_data_value(self, name, value):
        self._object._write(name, _value_for_scene(value))

    def _live_array(self, name):
        if self._object._binding is not None and name in ("position", "velocity") and self._object.type == "MechanicalObject":
            if name == "position" and self._object._is_rigid():
                return None  # (n, 7) rows are a copy: writeableArray writes them back
            return self._object._read(name)
        return None

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        method = object_methods(self._object.type).get(name)
        if method is not None:
            return lambda *args, **kwargs: method(self, *args, **kwargs)
        if self._has_data(name):
            return Data(self, name)
        raise AttributeError(f"{self.getPathName()} ({self._object.type}) has no data or method '{name}'"
                             f"{_closest(name, self._object.data_names())}")

    def __setattr__(self, name, value):
        if name.startswith("_"):
            object.__setattr__(self, name, value)
        else:
            self._set_data_value(name, value.value if isinstance(value, Data) else value)

    def __repr__(self):
        return f"<Sofa.Core.Object {self._object.type} {self.getPathName()}>"


Object = BaseObject


ForceFieldVec3d = ForceField


class Node:
    """A node of the scene: children, objects (components and controllers) and its data (dt, gravity)."""

    def __init__(self, name="root", **data):
        self._bind(fastcorot.Node(name))
        object.__setattr__(self._node, "_location", _scene._caller_location())
        for key, value in data.items():  # the node's data (dt, gravity, ...), as SofaPython3's Node(name, **data)
            setattr(self, key, value)

    def _bind(self, node):
        object.__setattr__(self, "_node", node)
        object.__setattr__(self, "_python_objects", [])  # controllers and force fields written in Python
        object.__setattr__(self, "_extra", {})  # node data without effect here (bbox, animate, ...)
        object.__setattr__(self, "_simulation", None)  # at the root: the running simulation (Sofa.Simulation)
        object.__setattr__(node, "_sofa", self)

    @staticmethod
    def _of(node):
        existing = getattr(node, "_sofa", None)
        if existing is not None:
            return existing
        wrapper = Node.__new__(Node)
        wrapper._bind(node)
        return wrapper

    @property
    def fastcorot_node(self):
        """The fastcorot.Node this wraps (what fastcorot.Simulation builds)."""
        return self._node

    # --- the tree ---------------------------------------------------------------------------------
    def addChild(self, child, **data):
        """A new child node of that name, its data (dt, gravity, activated, ...) from the keywords
        as SofaPython3's; or `child`, a Node made apart."""
        if isinstance(child, Node):
            if child._node._parent is self._node:
                return child
            if child._node._parent is not None:
                _add_parent(child._node, self._node)
                self._changed_while_running()
                return child
            object.__setattr__(child._node, "_parent", self._node)
            self._node._children.append(child._node)
            _graft_links(child._node)
            self._changed_while_running()
            return child
        if not isinstance(child, str):
            raise TypeError(f"addChild: expected a name (str) or a Sofa.Core.Node, got {type(child).__name__}")
        self._changed_while_running()
        node = fastcorot.Node(child)
        object.__setattr__(node, "_location", _scene._caller_location())
        object.__setattr__(node, "_parent", self._node)
        self._node._children.append(node)
        added = Node._of(node)
        for name, value in data.items():  # SofaPython3 fills the node's data from the keywords
            if name in _NODE_DATA and name != "time":
                added._set_data_value(name, value.value if isinstance(value, Data) else value)
            else:
                warnings.warn(f"{added.getPathName()}: addChild: data '{name}' not used (a node's data are "
                              f"{', '.join(d for d in _NODE_DATA if d != 'time')}){_closest(name, _NODE_DATA)}",
                              _scene.SceneWarning, stacklevel=2)
        return added

    createChild = addChild

    def addObject(self, type_name, *args, **data):
        """A component by type name and data (str, numbers, lists, numpy arrays, links as "@path" or
        as Data, objects or nodes), or a Python Controller or ForceField. Checked against fastcorot's component
        table: an unknown type is a ValueError naming the closest; unknown data warn (SceneWarning)."""
        if isinstance(type_name, _PythonComponent):
            self._changed_while_running()
            type_name.__dict__["_sofa_context"] = self
            self._python_objects.append(type_name)
            return type_name
        if not isinstance(type_name, str):
            raise TypeError(f"addObject: expected a component type (str) or a Sofa.Core.Controller, got "
                            f"{type(type_name).__name__}")
        if args:
            raise TypeError(f"addObject('{type_name}'): data are keyword arguments, got {len(args)} positional")
        self._changed_while_running()
        location = _scene._caller_location()
        values = {key: _value_for_scene(value) for key, value in data.items()}
        if str(values.get("template", "")).startswith("Rigid") or (type_name != "MechanicalObject" and "template" not in values
                                                                    and self._context_template().startswith("Rigid")):
            # 7 numbers per rigid frame: kept as text, for the builder to refuse where it is simulated
            values = {key: value if isinstance(value, str) else to_text(value) for key, value in values.items()}
        wrapped = _scene.Object(self._node, type_name, values, location, strict=False)
        self._node._objects.append(wrapped)
        return BaseObject._of(wrapped, self)

    createObject = addObject

    def _context_template(self):
        """The template of the node's context state (its first MechanicalObject, or the nearest
        ancestor's), which SOFA gives the components created without one ("" for none)."""
        node = self._node
        while node is not None:
            for obj in node._objects:
                if obj.type == "MechanicalObject":
                    return str(obj._data.get("template", "Vec3d"))
            node = node._parent
        return ""

    def _changed_while_running(self):
        """The tree changed after Sofa.Simulation.init: the simulation is built again, the running
        state carried over, at the next init() of a node or before the next step."""
        root = self.getRoot()
        if root._simulation is not None:
            root._extra["_grown"] = True

    def getRoot(self):
        node = self._node
        while node._parent is not None:
            node = node._parent
        return Node._of(node)

    def getChild(self, name):
        for child in self._node._children:
            if child.name == name:
                return Node._of(child)
        for child in getattr(self._node, "_alias_children", ()):  # moved below a second parent
            if child.name == name and child._parent is not self._node:
                return Node._of(child)
        return None

    def getObject(self, name, **kwargs):
        """The object (or Python component) of that name, None without one; SofaPython3's extra
        keywords (``warning=False``) are accepted and have no effect. An object given no name is
        found by its type's, as SOFA names it (``root.VisualStyle``)."""
        for obj in self._node._objects:
            if obj._data.get("name") == name:
                return BaseObject._of(obj, self)
        for obj in self._node._objects:
            own = obj._data.get("name")
            if not (isinstance(own, str) and own) and obj.type == name:
                return BaseObject._of(obj, self)
        for controller in self._python_objects:
            if controller.getName() == name:
                return controller
        return None

    def hasObject(self, name):
        return self.getObject(name) is not None

    @property
    def children(self):
        return _NamedList(Node._of(child) for child in self._node._children)

    @property
    def objects(self):
        return _NamedList([BaseObject._of(obj, self) for obj in self._node._objects] + list(self._python_objects))

    @property
    def parents(self):
        return _NamedList([Node._of(self._node._parent)] if self._node._parent is not None else [])

    def getName(self):
        return self._node.name

    def getPathName(self):
        """SOFA's path: "/" for the root, "/Liver/Visu" below it."""
        names = [node.name for node in self._node._lineage()[1:]]
        return "/" + "/".join(names)

    def _sofa_path(self, name):
        path = self.getPathName()
        return (path if path != "/" else "") + "/" + name

    def getLinkPath(self):
        return "@" + self.getPathName()

    def init(self):
        """SOFA initialises a node added while the scene runs: here the scene is built again from
        the grown tree and the running state carried over (fastcorot.Simulation.rebuild); before
        Sofa.Simulation.init, nothing to do."""
        root = self.getRoot()
        if root._simulation is not None and root._extra.get("_grown"):
            from . import Simulation
            Simulation._regrow(root)

    def getData(self, name):
        return Data(self, name) if name in _NODE_DATA or name in self._extra.get("_added", ()) else None

    findData = getData

    def addData(self, name, value=None, default=None, help="", group="", type=""):
        """A datum of the node's own (SofaPython3's Node.addData, what prefabs' parameters are): then
        ``node.<name>`` is a Data; a component given it as a value takes its value."""
        if not isinstance(name, str) or not name.isidentifier():
            raise TypeError(f"{self.getPathName()}: addData: name must be an identifier, got {name!r}")
        value = value if value is not None else default
        if isinstance(type, str) and type.startswith("Vec") and value is not None and not isinstance(value, str):
            import numpy as np

            value = np.array(value, dtype=float)  # SofaPython3 reads vector data back as arrays
        self._extra.setdefault("_added", set()).add(name)
        self._extra[name] = value
        return Data(self, name)

    def _first(self, category):
        for obj in self._node._objects:
            spec = _core.component_spec(obj.type)
            if spec and spec["category"] == category:
                yield BaseObject._of(obj, self)

    def getMechanicalState(self):
        """The node's MechanicalObject (None without one)."""
        return next(self._first("state"), None)

    def getMass(self):
        return next(self._first("mass"), None)

    def getForceField(self, index):
        fields = list(self._first("forcefield"))
        return fields[index] if 0 <= index < len(fields) else None

    def removeChild(self, child):
        """Removes a child node (a Node or its name); while the scene runs, the simulation is built
        again without it before the next step."""
        node = child._node if isinstance(child, Node) else next((c for c in self._node._children if c.name == child), None)
        if node is None or node not in self._node._children:
            raise ValueError(f"{self.getPathName()}: removeChild: no child {child!r}")
        self._node._children.remove(node)
        object.__setattr__(node, "_parent", None)
        self._changed_while_running()

    def removeObject(self, obj):
        """Removes an object (or a Python controller or force field); while the scene runs, the
        simulation is built again without it before the next step."""
        if isinstance(obj, BaseObject) and obj._object in self._node._objects:
            self._node._objects.remove(obj._object)
        elif obj in self._python_objects:
            self._python_objects.remove(obj)
        else:
            raise ValueError(f"{self.getPathName()}: removeObject: {obj!r} is not in this node")
        self._changed_while_running()

    # --- data (the owner protocol of Data) ----------------------------------------------------------
    def _data_value(self, name):
        if name == "name":
            return self._node.name
        if name in ("dt", "gravity"):
            return getattr(self.getRoot()._node if self._node._parent is not None and name == "dt" else self._node, name)
        if name == "activated":
            return self._node.activated
        if name == "time":
            root = self.getRoot()
            if root._simulation is None:
                return 0.0
            return root._simulation.time + root._extra.get("_time_offset", 0.0)
        return self._extra.get(name)

    def _set_data_value(self, name, value):
        if name == "name":
            self._node.name = value
        elif name in ("dt", "gravity"):
            setattr(self._node, name, value)
        elif name == "activated":  # while the scene runs, it is built again without (or with) the subtree
            was = self._node.activated
            self._node.activated = value
            if was and not self._node.activated:
                self._freeze_states()
            self._changed_while_running()
        elif name == "time":
            raise AttributeError(f"{self.getPathName()}: time is read-only (it advances with the steps)")
        else:
            self._extra[name] = value

    def _live_array(self, name):
        return None

    def _freeze_states(self):
        """The subtree is being deactivated while the scene runs: SOFA leaves its states where they
        are, so each simulated MechanicalObject below keeps its current rest, position and velocity
        as its data (what it reads afterwards, and starts from when activated again)."""
        for node in _scene.walk(self._node):
            for obj in node._objects:
                if obj.type == "MechanicalObject" and obj._binding is not None:
                    for name in ("rest_position", "position", "velocity"):
                        obj._data[name] = np.array(obj._read(name))

    # --- attribute access: children, objects, controllers, then data ------------------------------
    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        found = self.getChild(name) or self.getObject(name)
        if found is not None:
            return found
        if name in _NODE_DATA or name in self._extra.get("_added", ()):
            return Data(self, name)
        names = [c.name for c in self._node._children] + [o._data.get("name") for o in self._node._objects]
        names = [n for n in names if isinstance(n, str)] + [c.getName() for c in self._python_objects]
        raise AttributeError(f"Node {self.getPathName()} has no child, object or data named '{name}'"
                             f"{_closest(name, names + list(_NODE_DATA))}")

    def __setattr__(self, name, value):
        if name.startswith("_"):
            object.__setattr__(self, name, value)
        elif name in _NODE_DATA or name in self._extra.get("_added", ()):
            self._set_data_value(name, value.value if isinstance(value, Data) else value)
        else:
            object.__setattr__(self, name, value)  # a Python attribute of the script's own, as SofaPython3 keeps

    def __repr__(self):
        return f"<Sofa.Core.Node {self.getPathName()}>"

    # --- what the animation loop calls (Sofa.Simulation and `fastcorot run script.py`) ------------
    def _all_python_components(self):
        found = list(self._python_objects)
        for child in self._node._children:
            found += Node._of(child)._all_python_components()
        return found

    def _all_controllers(self):
        return [c for c in self._all_python_components() if isinstance(c, Controller)]

    def _send(self, event_type, **fields):
        """Sends an event to every controller below, in scene order: its on<Type> method, else onEvent."""
        event = {"type": event_type, "isHandled": False, **fields}
        for controller in self._all_controllers():
            method = getattr(controller, "on" + event_type, None) or getattr(controller, "onEvent", None)
            if method is not None:
                method(event)


# SofaPython3's Data subclasses by value kind (texts, vectors, lists of texts): one class here, so
# that isinstance checks scripts make hold.
DataString = DataContainer = DataVectorString = Data

__all__ = ["BaseObject", "Controller", "Data", "DataContainer", "DataString", "DataVectorString", "ForceField",
           "ForceFieldVec3d", "Node", "Object"]


def __getattr__(name):
    raise AttributeError(f"Sofa.Core.{name}: SofaPython3 has it, fastcorot's Sofa package does not (docs/python.md lists "
                         "what maps)")
