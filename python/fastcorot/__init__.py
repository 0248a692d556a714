"""fastcorot: fast corotational tetrahedral finite elements, SOFA's FastTetrahedralCorotationalForceField,
from Python.

- ``fastcorot.ForceField(points, tetrahedra, ...)``: the force field on numpy arrays (forces, the
  stiffness product, the assembled stiffness, energy, rotations), in float32 or float64.
- ``fastcorot.Node``, ``fastcorot.load``: scenes in SofaPython3's shape, or read from .scn files.
- ``fastcorot.Simulation(root)``: build and step a scene; states are numpy views.

Errors raise ValueError, TypeError or FileNotFoundError with the messages of the command line.
"""

from ._core import ForceField, SimulationError, component_documentation
from .scene import Node, Object, load
from .simulation import Simulation

__all__ = ["ForceField", "Node", "Object", "Simulation", "SimulationError", "component_documentation", "load"]
