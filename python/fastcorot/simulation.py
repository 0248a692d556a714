"""fastcorot.Simulation: a scene tree built into a running simulation and stepped.

    sim = fastcorot.Simulation(root)
    sim.step(100)
    root.beam.dofs.position      # (n, 3) numpy view of the state, no copy

Building goes through the scene builder of `fastcorot run`, so a scene assembled in Python and the
same scene read from a .scn file step identically. Errors in the scene are ValueError (a missing
mesh file FileNotFoundError) with the command line's messages; a state that turns non-finite while
stepping is fastcorot.SimulationError (a RuntimeError) naming the step and the object.
"""

import numbers

from . import _core
from .scene import Node, walk


class Simulation:
    """The simulation of a scene tree (`root`: a fastcorot.Node, usually the root). Building it
    binds the tree's simulated MechanicalObjects to the simulation's state (their position and
    velocity become views of it) and the root's dt and gravity to the simulation's; a later
    Simulation built from the same tree takes the bindings over."""

    def __init__(self, root, threads=None, strict=True, allow_empty=False):
        """`threads`: None (the default) for fastcorot's choice, as `fastcorot run` makes it: one
        thread per 2,000 simulated points, at most every core; parallel loops use fewer while other
        processes keep cores busy. `strict`: unknown attributes are
        errors (False: warnings, listed in `warnings`, as SOFA and `fastcorot run` take them);
        `allow_empty`: a scene with nothing to simulate steps only time."""
        if not isinstance(root, Node):
            raise TypeError(f"Simulation: expected a fastcorot.Node, got {type(root).__name__}")
        objects = []
        core = _core.SimulationCore(root._tree(objects), strict, allow_empty)
        if threads is None:
            threads = _core.default_thread_count(sum(size for _, _, _, size in core.state_parts))
        core.threads = threads
        self._strict = strict
        self._allow_empty = allow_empty
        self._bind(root, core, objects)

    def rebuild(self):
        """Builds the scene again from its tree, grown or pruned since (nodes and objects added or
        removed between steps, as SofaPython3 scripts do), and carries the running state over: the
        step count, and the positions, velocities and solver states of every object still in the
        tree (matched by node path); new objects start from the scene. Returns a dict: "carried"
        and "fresh" (node paths) and "notes" (what starts afresh). The previous state stays valid
        for arrays that view it (they no longer follow the simulation)."""
        objects = []
        report = self._core.rebuild(self._root._tree(objects), self._strict, self._allow_empty)
        self._bind(self._root, self._core, objects)
        return report

    def _bind(self, root, core, objects):
        # Objects bound before and removed from the tree since must not view the rebuilt state.
        for obj in getattr(self, "_bound", ()):
            for key in ("_binding", "_mapped", "_lagrangian"):
                object.__setattr__(obj, key, None)
        for node in walk(root):
            object.__setattr__(node, "_core", None)
            for obj in node._objects:
                object.__setattr__(obj, "_binding", None)
                object.__setattr__(obj, "_mapped", None)
                object.__setattr__(obj, "_lagrangian", None)
        self._bound = list(objects)
        # Each MechanicalObject views its range of its simulated object's state (several objects
        # under one solver are one state, theirs one after the other).
        for rank, k, offset, size in core.state_parts:
            object.__setattr__(objects[rank], "_binding", (core, k, offset, offset + size))
        # A mapped MechanicalObject with a name reads what its mapping gives (the states' key is
        # "node path/object name").
        mapped = {key for key, entry in core.states().items() if entry["mapped"]}
        for node in walk(root):
            for obj in node._objects:
                name = obj._data.get("name")
                key = f"{node.path}/{name}"
                if obj.type == "MechanicalObject" and obj._binding is None and isinstance(name, str) and key in mapped:
                    object.__setattr__(obj, "_mapped", (core, key))
        # Under a FreeMotionAnimationLoop: the constraint solver reads the last step's figures, and
        # the Lagrangian constraints read and write what scripts change between steps.
        for index, rank in enumerate(core.constraint_objects):
            object.__setattr__(objects[rank], "_lagrangian", (core, index))
        if core.constraint_solver_object >= 0:
            object.__setattr__(objects[core.constraint_solver_object], "_lagrangian", (core, None))
        # Force fields cut the object whose state is in their node or the nearest node above.
        bound = {id(objects[rank]): k for rank, k, _, _ in core.state_parts}

        def bind_force_fields(node, k):
            for obj in node._objects:
                if id(obj) in bound:
                    k = bound[id(obj)]
            for obj in node._objects:
                if obj.type in ("FastTetrahedralCorotationalForceField", "TetrahedronFEMForceField") and k is not None:
                    object.__setattr__(obj, "_binding", (core, k))
            for child in node._children:
                bind_force_fields(child, k)

        bind_force_fields(root, None)
        object.__setattr__(root, "_core", core)
        self._core = core
        self._root = root
        self._states = [objects[rank] for rank in core.state_objects]
        self._parts = [objects[rank] for rank, _, _, _ in core.state_parts]

    def step(self, n=1):
        """Advances n time steps (each object in scene order, then time by dt). The GIL is released
        while stepping; Ctrl-C stops between steps."""
        if isinstance(n, bool) or not isinstance(n, numbers.Integral):
            raise TypeError(f"step: n must be an integer, got {type(n).__name__} {n!r}")
        self._core.step(int(n))

    @property
    def root(self):
        return self._root

    @property
    def objects(self):
        """The MechanicalObject of each simulated object, in scene order."""
        return list(self._states)

    @property
    def paths(self):
        """The node path of each simulated object ("root/beam"), as `fastcorot run --dump-state` names them."""
        return self._core.paths

    def states(self):
        """Every MechanicalObject of the scene, mapped ones included, at the current step, as
        `fastcorot run --dump-state` writes one dumped step under "states": a dict keyed
        "node path/object name" in scene order, each {"node", "object", "mapped", "position",
        "velocity"} with (n, 3) numpy copies. `json.dump` of {"dt": sim.dt, "states": {str(step):
        {key: {..., "position": p.tolist(), ...}}}} writes the command line's format."""
        return self._core.states()

    def contacts(self):
        """The contacts the last step's collision detection kept (a scene with a CollisionPipeline),
        in solve order, as `fastcorot run --dump-state` writes one dumped step under "contacts": a
        dict {"count": n, "points": (n, 2, 3) numpy copy, each contact's point on its first element
        then on its second, "normals": (n, 3), unit, from the first element to the second}. The
        points are where detection found them, at the step's start. Count 0 before the first step
        and without a collision pipeline."""
        return self._core.contacts()

    def collision_report(self):
        """What the last step's collision detection did: a dict {"contacts", "model_pairs",
        "element_pairs", "degenerate_elements", "detection_seconds", "crossed", "deepest_crossing"} (the run summary's figures;
        zeros without a collision pipeline)."""
        return self._core.collision_report()

    def tetrahedra(self, index=0):
        """(m, 4) tetrahedra of simulated object `index` (its force field's mesh; empty without one),
        indices into its MechanicalObject's points."""
        return self._core.tetrahedra(index)

    @property
    def time(self):
        return self._core.time

    @property
    def steps_done(self):
        return self._core.steps_done

    @property
    def dt(self):
        return self._core.dt

    @dt.setter
    def dt(self, value):
        self._root.dt = value

    @property
    def gravity(self):
        return self._root.gravity

    @gravity.setter
    def gravity(self, value):
        self._root.gravity = value

    @property
    def threads(self):
        """Threads: independent objects (one per solver node) concurrently, the rest to each object's
        kernels; results are bitwise the same for any count. Loops use fewer while other processes
        keep cores busy."""
        return self._core.threads

    @threads.setter
    def threads(self, value):
        self._core.threads = value

    @property
    def warnings(self):
        """One line per unknown attribute ignored (with strict=False)."""
        return list(self._core.warnings)

    @property
    def info(self):
        """One line per component or node the builder ignored (display, collision, unsolved nodes)."""
        return list(self._core.info)

    def __repr__(self):
        return f"<fastcorot.Simulation of {self._root.path}: {len(self._states)} objects, t = {self.time:g}>"
