"""Sofa.Simulation: build and step a scene (SofaPython3's init / initRoot / animate / reset / unload).

init(root) builds the scene tree into a fastcorot.Simulation (after it, simulated MechanicalObjects'
position and velocity are views of the state) and calls each controller's init(); animate(root, dt)
sends AnimateBeginEvent to the controllers, steps once, and sends AnimateEndEvent, as SOFA's
DefaultAnimationLoop does.
"""

import warnings

import fastcorot
from fastcorot.scene import SceneWarning, walk

from ._matrices import bound_state, canonical_type
from .Core import ForceField, Node


def _root(node):
    if not isinstance(node, Node):
        raise TypeError(f"expected a Sofa.Core.Node, got {type(node).__name__}")
    return node.getRoot()


def _start(root, strict=False):
    simulation = fastcorot.Simulation(root.fastcorot_node, strict=strict, allow_empty=True)
    object.__setattr__(root, "_simulation", simulation)
    root._extra.pop("_time_offset", None)
    root._extra.pop("_grown", None)
    for component in root._all_python_components():
        component.__dict__.pop("_fastcorot_initialised", None)
    _attach(root, simulation)
    return simulation


def _attach(root, simulation):
    """What the built simulation takes from the Python side: its Python force fields, the solves the
    linear systems read; then each Python component not yet initialised gets its init()."""
    if any(canonical_type(obj.type) == "MatrixLinearSystem" for node in walk(root.fastcorot_node) for obj in node._objects):
        simulation._core.record_solves()  # for the linear systems' get_system_matrix and the like
    for component in root._all_python_components():
        if isinstance(component, ForceField):
            state = bound_state(component.getContext().fastcorot_node)
            if state is not None:  # else its node is not simulated (no solver, or an empty state), as in SOFA
                core, k, start, stop = state
                core.add_python_force_field(k, component, component.getName(), start, stop)
    for component in root._all_python_components():
        if not component.__dict__.get("_fastcorot_initialised"):
            component.__dict__["_fastcorot_initialised"] = True
            component.init()


def _regrow(root):
    """The tree changed while running (nodes or objects added or removed): the simulation is built
    again from it, the running state carried over (fastcorot.Simulation.rebuild), and the new Python
    components initialised, as SOFA initialises a node added at run time."""
    simulation = root._simulation
    report = simulation.rebuild()  # raises, the running scene kept, when the grown tree cannot run
    root._extra.pop("_grown", None)
    for line in report["warnings"]:
        warnings.warn(line, SceneWarning, stacklevel=3)
    for note in report["notes"]:
        warnings.warn(f"the scene was built again while running: {note}", SceneWarning, stacklevel=3)
    _attach(root, simulation)


def init(node):
    """Builds the simulation of node's scene (unknown attributes were warnings at addObject). On a
    scene already running (SOFA initialises a node added to it), the tree's changes are taken in
    with the running state carried over; nothing restarts."""
    root = _root(node)
    if root._simulation is not None:
        if root._extra.get("_grown"):
            _regrow(root)
        return
    _start(root)


initRoot = init


def simulation_of(node):
    """The fastcorot.Simulation running node's scene; RuntimeError before init."""
    simulation = _root(node)._simulation
    if simulation is None:
        raise RuntimeError(f"{node.getPathName()}: the scene is not initialised: call Sofa.Simulation.init(root) first")
    return simulation


def animate(node, dt=0.0):
    """One step of `dt` (0: the root's dt) with the controllers' AnimateBeginEvent and AnimateEndEvent."""
    root = _root(node)
    simulation = simulation_of(root)
    if root._extra.get("_grown"):
        _regrow(root)
    step = float(dt) if dt else simulation.dt
    if not step > 0:
        raise ValueError(f"Sofa.Simulation.animate: dt = {dt!r}: must be > 0")
    root._send("AnimateBeginEvent", dt=step)
    if step != simulation.dt:  # SOFA's animate(root, dt) steps by dt, leaving the root's dt
        previous = simulation.dt
        simulation._core.dt = step
        try:
            simulation.step()
        finally:
            simulation._core.dt = previous
        # The simulation counts time as steps x dt: the difference is the root's to add.
        root._extra["_time_offset"] = root._extra.get("_time_offset", 0.0) + step - previous
    else:
        simulation.step()
    root._send("AnimateEndEvent", dt=step)


def reset(node):
    """Back to the start: the simulation is built again from the scene tree, then each controller's
    reset() is called."""
    root = _root(node)
    simulation_of(root)
    _start(root)
    for controller in root._all_controllers():
        controller.reset()


def unload(node):
    """Drops the simulation (the tree stays; init builds it again)."""
    object.__setattr__(_root(node), "_simulation", None)


def initVisual(node):
    """Accepted: fastcorot's pictures and viewer draw from the simulation itself."""


updateVisual = initVisual
initTextures = initVisual


def __getattr__(name):
    raise AttributeError(f"Sofa.Simulation.{name}: SofaPython3 has it, fastcorot's Sofa package does not (it has init, "
                         "initRoot, animate, reset, unload, initVisual, updateVisual)")
