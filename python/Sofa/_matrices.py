"""The matrix access of SofaPython3's components, as scipy.sparse matrices over the points of the
component's own MechanicalObject: a force field's assembleKMatrix() (df/dx, SOFA's sign), a mass's
assembleMMatrix(); a MatrixLinearSystem's A() (or
get_system_matrix(), get_rhs_vector() and get_solution_vector() give its last solve (the
Sofa package records the solves of a scene that has one)."""

from fastcorot import _core
from fastcorot import scene as _scene


def canonical_type(type_name):
    """A type's name in the component table (an alias resolved), else the type as written."""
    spec = _scene._spec(type_name)
    return spec[0] if spec else type_name


def _category(type_name):
    spec = _core.component_spec(type_name)
    return spec["category"] if spec else ""


def bound_state(node):
    """(core, k, start, stop) of the simulated MechanicalObject nearest a fastcorot node (it, then up); None if none."""
    while node is not None:
        for obj in node._objects:
            if obj.type == "MechanicalObject" and obj._binding is not None:
                return obj._binding
        node = node._parent
    return None


def _state_of(sofa_object):
    """(core, k, start, stop) of the simulated MechanicalObject nearest the object (its node, then up)."""
    state = bound_state(sofa_object.fastcorot_object.node)
    if state is not None:
        return state
    raise RuntimeError(f"{sofa_object.getPathName()}: not part of a running simulation: call "
                       "Sofa.Simulation.init(root) first (and give its node a solver and a MechanicalObject)")


def _document_order(node):
    yield from node._objects
    for child in node._children:
        yield from _document_order(child)


def assemble_k_matrix(sofa_object):
    core, k, _, _ = _state_of(sofa_object)
    wanted = canonical_type(sofa_object.getClassName())
    candidates = [i for i, name in enumerate(core.force_field_types(k)) if name == wanted]
    if not candidates:
        raise NotImplementedError(f"{sofa_object.getPathName()}: assembleKMatrix: {wanted} has no stiffness matrix "
                                  "in fastcorot (a load or a constraint, not an elastic force field)")
    # The force fields of one type on one simulated object are in scene order.
    root = sofa_object.fastcorot_object.node
    while root._parent is not None:
        root = root._parent
    peers = [obj for obj in _document_order(root)
             if canonical_type(obj.type) == wanted and (bound_state(obj.node) or (None, None))[1] == k]
    return core.stiffness_matrix(k, candidates[peers.index(sofa_object.fastcorot_object)])


def assemble_m_matrix(sofa_object):
    core, k, start, stop = _state_of(sofa_object)
    return core.mass_matrix(k, start, stop)


def _solver_object(sofa_object):
    """(core, k) of the simulated object whose ODE solver sits at or above the linear system's node."""
    simulation = sofa_object.getContext().getRoot()._simulation
    if simulation is None:
        raise RuntimeError(f"{sofa_object.getPathName()}: the scene is not initialised: call Sofa.Simulation.init(root)")
    node = sofa_object.fastcorot_object.node
    paths = simulation.paths
    while node is not None:
        if any(_category(obj.type) == "odesolver" for obj in node._objects) and node.path in paths:
            return simulation._core, paths.index(node.path)
        node = node._parent
    raise RuntimeError(f"{sofa_object.getPathName()}: no simulated ODE solver at or above its node")


def _flag(sofa_object, name):
    value = sofa_object.fastcorot_object._read(name)
    return True if value is None else bool(value)


def _last_solve(sofa_object):
    core, k = _solver_object(sofa_object)
    last = core.last_solve(k)
    if last is None:
        raise RuntimeError(f"{sofa_object.getPathName()}: no linear solve yet (the system is filled by a step)")
    return core, k, last


def system_matrix(sofa_object):
    """The system matrix of the last solve, with the linear system's own choices (assembleMass,
    assembleStiffness, assembleDamping, applyProjectiveConstraints): a scipy.sparse matrix, or a
    numpy array for template FullMatrix."""
    core, k, ((m, b, kf), _, _) = _last_solve(sofa_object)
    m = m if _flag(sofa_object, "assembleMass") else 0.0
    b = b if _flag(sofa_object, "assembleDamping") else 0.0
    kf = kf if _flag(sofa_object, "assembleStiffness") else 0.0
    if _flag(sofa_object, "applyProjectiveConstraints"):
        matrix = core.system_matrix(k, m, b, kf)
    elif b == 0 and kf == 0:
        size = core.position(k).shape[0]
        matrix = core.mass_matrix(k, 0, size) * m
    else:
        raise NotImplementedError(f"{sofa_object.getPathName()}: applyProjectiveConstraints=False with stiffness or "
                                  "damping assembled: fastcorot assembles those projected only")
    if sofa_object.getTemplateName() == "FullMatrix":
        return matrix.toarray()
    return matrix


def rhs_vector(sofa_object):
    return _last_solve(sofa_object)[2][1]


def solution_vector(sofa_object):
    return _last_solve(sofa_object)[2][2]


_LINEAR_SYSTEM_CALLS = {"A": system_matrix, "get_system_matrix": system_matrix, "b": rhs_vector,
                        "get_rhs_vector": rhs_vector, "x": solution_vector, "get_solution_vector": solution_vector}


def object_methods(type_name):
    """{name: function(sofa_object, ...)} of the calls an object of this type has beyond its data."""
    category = _category(type_name)
    if category == "forcefield":
        return {"assembleKMatrix": assemble_k_matrix}
    if category == "mass":
        return {"assembleMMatrix": assemble_m_matrix}
    if canonical_type(type_name) == "MatrixLinearSystem":
        return dict(_LINEAR_SYSTEM_CALLS)
    return {}
