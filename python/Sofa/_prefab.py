"""Sofa.Prefab: a node that builds its own content, as SofaPython3's (what STLIB's
ElasticMaterialObject, VisualModel and SoftRobots' parts are). A subclass lists its parameters:

    class Finger(Sofa.Prefab):
        prefabParameters = [{"name": "youngModulus", "type": "double", "help": "E", "default": 18000}]

        def init(self):
            self.addObject("MechanicalObject", name="dofs")
            self.addObject("TetrahedronFEMForceField", youngModulus=self.youngModulus.value)

    root.addChild(Finger(name="finger", youngModulus=5000))

Construction: a node named `name` (the class's name by default); each entry of prefabParameters
and prefabData (and the older `properties`) becomes a datum of the node (``self.youngModulus``), set
from the keyword argument of that name or its default; `parent=` (or `parents=`) adds the prefab
under that node; then init() builds the content. Other keyword arguments are ignored, as in
SofaPython3. A parameter written after construction does not rebuild the content (SofaPython3
empties the node instead; no script relies on either).
"""

from . import Helper
from .Core import Node


class Prefab(Node):
    prefabParameters = []
    prefabData = []
    properties = []  # SofaPython3's older name for prefabParameters

    def __init__(self, *args, **kwargs):
        name = kwargs.get("name", type(self).__name__)
        Node.__init__(self, name.value if hasattr(name, "value") else str(name))
        if type(self).properties:
            Helper.msg_deprecated(self, "'properties' is deprecated: use 'prefabParameters'")
        for entry in [*type(self).prefabParameters, *type(self).properties, *type(self).prefabData]:
            if not isinstance(entry, dict) or "name" not in entry:
                raise TypeError(f"{type(self).__name__}: each prefab parameter is a dict with a 'name', got {entry!r}")
            self.addData(name=entry["name"], value=kwargs.get(entry["name"], entry.get("default")),
                         help=entry.get("help", ""), group=entry.get("group", "Prefab's properties"), type=entry.get("type", ""))
        parent, parents = kwargs.get("parent"), kwargs.get("parents")
        if parent is not None and parents is not None:
            Helper.msg_error(self, "a prefab takes parent= or parents=, not both")
        elif parent is not None:
            parent.addChild(self)
        elif parents:
            parents[0].addChild(self)
            for other in parents[1:]:
                other.addChild(self)
        self.init()

    def init(self):
        """Builds the prefab's content: subclasses define it."""
