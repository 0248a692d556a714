"""The matrix access of SofaPython3's components, as scipy.sparse matrices over the points of the
component's own MechanicalObject: a force field's assembleKMatrix() (df/dx, SOFA's sign), a mass's
assembleMMatrix(). fastcorot's linear systems are inside its solvers: MatrixLinearSystem's A(),
get_system_matrix() and the like raise NotImplementedError naming the call."""

from fastcorot import _core
from fastcorot import scene as _scene

_LINEAR_SYSTEM_CALLS = ("A", "b", "x", "get_system_matrix", "get_rhs_vector", "get_solution_vector")


def _canonical(type_name):
    spec = _scene._spec(type_name)
    return spec[0] if spec else type_name


def _category(type_name):
    spec = _core.component_spec(type_name)
    return spec["category"] if spec else ""


def _state_of(sofa_object):
    """(core, k, start, stop) of the simulated MechanicalObject nearest the object (its node, then up)."""
    node = sofa_object.fastcorot_object.node
    while node is not None:
        for obj in node._objects:
            if obj.type == "MechanicalObject" and obj._binding is not None:
                return obj._binding
        node = node._parent
    raise RuntimeError(f"{sofa_object.getPathName()}: not part of a running simulation: call "
                       "Sofa.Simulation.init(root) first (and give its node a solver and a MechanicalObject)")


def _document_order(node):
    yield from node._objects
    for child in node._children:
        yield from _document_order(child)


def assemble_k_matrix(sofa_object):
    core, k, _, _ = _state_of(sofa_object)
    wanted = _canonical(sofa_object.getClassName())
    candidates = [i for i, name in enumerate(core.force_field_types(k)) if name == wanted]
    # Objects of the same type on the same simulated object come in scene order.
    root = sofa_object.fastcorot_object.node
    while root._parent is not None:
        root = root._parent
    rank = 0
    if len(candidates) > 1:
        peers = []
        for obj in _document_order(root):
            if _canonical(obj.type) != wanted:
                continue
            wrapper = getattr(obj, "_sofa", None)
            if wrapper is not None and _state_of(wrapper)[1] == k:
                peers.append(obj)
        rank = peers.index(sofa_object.fastcorot_object) if sofa_object.fastcorot_object in peers else 0
    if not candidates:
        raise NotImplementedError(f"{sofa_object.getPathName()}: assembleKMatrix: {wanted} has no stiffness matrix "
                                  "in fastcorot (a load or a constraint, not an elastic force field)")
    return core.stiffness_matrix(k, candidates[rank])


def assemble_m_matrix(sofa_object):
    core, k, start, stop = _state_of(sofa_object)
    return core.mass_matrix(k, start, stop)


def _not_available(call):
    def refuse(sofa_object, *args, **kwargs):
        raise NotImplementedError(
            f"{sofa_object.getPathName()}: {sofa_object.getClassName()}.{call}(): fastcorot's linear systems are "
            "inside its solvers and not exposed; assemble with a force field's assembleKMatrix() and a mass's "
            "assembleMMatrix()")
    return refuse


def object_methods(type_name):
    """{name: function(sofa_object, ...)} of the calls an object of this type has beyond its data."""
    category = _category(type_name)
    if category == "forcefield":
        return {"assembleKMatrix": assemble_k_matrix}
    if category == "mass":
        return {"assembleMMatrix": assemble_m_matrix}
    if type_name in ("MatrixLinearSystem", "CompositeLinearSystem", "LinearSystem"):
        return {call: _not_available(call) for call in _LINEAR_SYSTEM_CALLS}
    return {}
