"""fastcorot.ForceField against `fastcorot probe` (the same case through the program's JSON path)
and against the properties its definition implies (SPEC.md): K dx = add_dforce(dx), f = -dE/dx for
the linear method, zero force and the applied rotation under a rigid motion, float32 = float64 to
single precision."""

import json
import sys

import numpy as np
import pytest
import scipy.sparse

import fastcorot
from conftest import REPOSITORY, run_cli

METHODS = ["qr", "polar", "polar2", "none"]


def probe_case():
    return json.loads((REPOSITORY / "examples/probe/single_tetrahedron.json").read_text())


def small_mesh():
    """Two hexahedral cells split into 12 tetrahedra (a 3 x 2 x 2 grid of points), deformed."""
    root = fastcorot.Node("root")
    node = root.add_child("grid")
    grid = node.add_object("RegularGridTopology", name="grid", n=[3, 2, 2], min=[0, 0, 0], max=[2, 1, 1])
    tets = node.add_object("TetrahedronSetTopologyContainer", name="tets")
    node.add_object("Hexa2TetraTopologicalMapping", input=grid, output=tets, swapping=True)
    node.add_object("MechanicalObject", name="dofs")
    node.add_object("EulerImplicitSolver")
    node.add_object("CGLinearSolver")
    node.add_object("FastTetrahedralCorotationalForceField", name="fem")
    sim = fastcorot.Simulation(root)
    points = np.array(node.dofs.rest_position)
    tetrahedra = sim.tetrahedra(0)
    rng = np.random.default_rng(7)
    return points, tetrahedra, points + 0.15 * rng.standard_normal(points.shape)


@pytest.mark.parametrize("method", METHODS)
def test_equals_probe_on_the_single_tetrahedron(method, tmp_path):
    case = probe_case()
    case["method"] = method
    (tmp_path / "case.json").write_text(json.dumps(case))
    run_cli("probe", tmp_path / "case.json", "-o", tmp_path / "out.json")
    expected = json.loads((tmp_path / "out.json").read_text())

    field = fastcorot.ForceField(np.array(case["points"], float), case["tetrahedra"], young_modulus=case["youngModulus"],
                                 poisson_ratio=case["poissonRatio"], method=method)
    x = np.array(case["x"])
    # The same code on the same doubles, printed by the program with round-trip precision: equal.
    np.testing.assert_array_equal(field.add_force(x), expected["force"])
    np.testing.assert_array_equal(field.add_dforce(np.array(case["dx"]), k_factor=case["kFactor"]), expected["dforce"])
    np.testing.assert_array_equal(field.rotations, expected["rotations"])
    assert field.potential_energy(x) == expected["energy"]
    np.testing.assert_array_equal(field.edges, expected["edges"])
    np.testing.assert_array_equal(field.rest_volumes, expected["restVolume"])
    stiffness = field.stiffness(x, k_factor=case["kFactor"])
    assert scipy.sparse.issparse(stiffness)
    size = expected["stiffness"]["size"]
    reference = np.zeros((size, size))
    for row, col, value in expected["stiffness"]["triplets"]:
        reference[row, col] = value
    np.testing.assert_array_equal(stiffness.toarray(), reference)


def test_rest_stiffness_blocks_are_specs_worked_example():
    # SPEC.md, "Rest state": points (0,0,0) (1,0,0) (0,1,0) (0,0,1), tetrahedron (2,3,1,0), E = 1000,
    # nu = 0.3, shape vectors s = (0,1,0) (0,0,1) (1,0,0) (-1,-1,-1), V = 1/6 (worked by hand from the
    # formulas; SPEC lists D_0 = diag(64.1026, 224.359, 64.1026), D_3 = 352.5641 on the diagonal and
    # 160.25641 off it, L_0 = [[0,0,0],[0,0,64.1026],[0,96.1538,0]], SOFA's values).
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], float)
    field = fastcorot.ForceField(points, [[2, 3, 1, 0]], young_modulus=1000, poisson_ratio=0.3)
    mu = 1000 / (2 * 1.3) / 6
    lam = 1000 * 0.3 / (1.3 * 0.4) / 6
    np.testing.assert_allclose(field.rest_volumes, [1 / 6], rtol=1e-14)
    stiffness = field.stiffness(points).toarray()
    block = lambda a, b: stiffness[3 * a:3 * a + 3, 3 * b:3 * b + 3]  # noqa: E731
    np.testing.assert_allclose(block(2, 2), -np.diag([mu, lam + 2 * mu, mu]), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(block(0, 0), -((lam + mu) * np.ones((3, 3)) + 3 * mu * np.eye(3)), rtol=1e-12)
    assert block(0, 0)[0, 0] == pytest.approx(-352.5641, abs=1e-4) and block(2, 2)[1, 1] == pytest.approx(-224.359, abs=1e-3)
    edge = np.array([[0, 0, 0], [0, 0, mu], [0, lam, 0]])  # L_0, local edge (0,1) = mesh edge (2,3)
    np.testing.assert_allclose(block(3, 2), -edge, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(block(2, 3), -edge.T, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(field.add_force(points), 0, atol=1e-12)
    np.testing.assert_allclose(field.rotations, [np.eye(3)], atol=1e-15)


def test_stiffness_matrix_times_dx_is_add_dforce():
    points, tetrahedra, x = small_mesh()
    field = fastcorot.ForceField(points, tetrahedra, young_modulus=1000, poisson_ratio=0.3, method="polar")
    dx = np.random.default_rng(3).standard_normal(points.shape)
    stiffness = field.stiffness(x, k_factor=-0.5)
    product = (stiffness @ dx.reshape(-1)).reshape(-1, 3)
    np.testing.assert_allclose(product, field.add_dforce(dx, k_factor=-0.5), rtol=0, atol=1e-12 * np.abs(product).max())
    np.testing.assert_allclose(stiffness.toarray(), stiffness.toarray().T, atol=1e-10 * abs(stiffness).max())


def test_force_is_minus_the_energy_gradient_for_the_linear_method():
    points, tetrahedra, x = small_mesh()
    field = fastcorot.ForceField(points, tetrahedra, young_modulus=1000, poisson_ratio=0.3, method="none")
    force = field.add_force(x)
    h = 1e-6
    gradient = np.zeros_like(x)
    for i in range(x.shape[0]):
        for k in range(3):
            step = np.zeros_like(x)
            step[i, k] = h
            gradient[i, k] = (field.potential_energy(x + step) - field.potential_energy(x - step)) / (2 * h)
    np.testing.assert_allclose(force, -gradient, rtol=0, atol=1e-6 * np.abs(force).max())


@pytest.mark.parametrize("method", ["qr", "polar", "polar2"])
def test_a_rigid_motion_gives_no_force_and_its_rotation(method):
    points, tetrahedra, _ = small_mesh()
    angle = 0.7
    rotation = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0], [0, 0, 1]])
    moved = points @ rotation.T + [3, -1, 2]
    field = fastcorot.ForceField(points, tetrahedra, young_modulus=1000, poisson_ratio=0.3, method=method)
    np.testing.assert_allclose(field.add_force(moved), 0, atol=1e-10)
    np.testing.assert_allclose(field.rotations, np.broadcast_to(rotation, field.rotations.shape), atol=1e-12)


def test_float32_computes_in_float32_and_agrees_with_float64():
    points, tetrahedra, x = small_mesh()
    double = fastcorot.ForceField(points, tetrahedra, young_modulus=1000, poisson_ratio=0.3)
    single = fastcorot.ForceField(points.astype(np.float32), tetrahedra, young_modulus=1000, poisson_ratio=0.3)
    assert single.dtype == np.float32 and double.dtype == np.float64
    force = single.add_force(x.astype(np.float32))
    assert force.dtype == np.float32
    reference = double.add_force(x)
    np.testing.assert_allclose(force, reference, rtol=0, atol=1e-4 * np.abs(reference).max())
    assert single.stiffness().dtype == np.float32
    assert single.rotations.dtype == np.float32


def test_without_scipy_the_stiffness_is_triplets(monkeypatch):
    points, tetrahedra, x = small_mesh()
    field = fastcorot.ForceField(points, tetrahedra)
    matrix = field.stiffness(x)
    monkeypatch.setitem(sys.modules, "scipy.sparse", None)  # makes `import scipy.sparse` fail
    rows, cols, values = field.stiffness(x)
    assert rows.shape == cols.shape == values.shape == (matrix.nnz,)
    dense = np.zeros(matrix.shape)
    dense[rows, cols] = values
    np.testing.assert_array_equal(dense, matrix.toarray())


def test_per_tetrahedron_parameters_and_explicit_edges_are_accepted():
    points, tetrahedra, x = small_mesh()
    uniform = fastcorot.ForceField(points, tetrahedra, young_modulus=800, poisson_ratio=0.2)
    listed = fastcorot.ForceField(points, tetrahedra, young_modulus=[800] * len(tetrahedra),
                                  poisson_ratio=np.full(len(tetrahedra), 0.2), edges=uniform.edges[::-1, ::-1])
    np.testing.assert_allclose(listed.add_force(x), uniform.add_force(x), rtol=0, atol=1e-12 * np.abs(x).max() * 800)


def test_two_python_threads_on_one_field_take_turns():
    """The methods give up the GIL while they compute; calls on one field from two threads must
    still give exactly the results of the same calls made one after another."""
    import threading

    points, tetrahedra, x = small_mesh()
    field = fastcorot.ForceField(points, tetrahedra, young_modulus=1000.0, poisson_ratio=0.3)
    rng = np.random.default_rng(3)
    positions = [x + 0.05 * rng.standard_normal(x.shape) for _ in range(4)]
    dx = rng.standard_normal(x.shape)
    expected = []
    for p in positions:
        force = field.add_force(p)
        expected.append((force, field.add_dforce(dx, 1.0)))
    failures = []

    def work(k):
        # A force depends on its positions only; K dx uses the linearisation of whichever
        # add_force came last (the other thread's may slip in between), so it must be one of the
        # sequential products, bit for bit.
        for _ in range(30):
            force = field.add_force(positions[k])
            if not np.array_equal(force, expected[k][0]):
                failures.append(("force", k))
            product = field.add_dforce(dx, 1.0)
            if not any(np.array_equal(product, e[1]) for e in expected):
                failures.append(("dforce", k))

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert failures == []


INTEGER_DTYPES = [np.int8, np.int16, np.int32, np.int64, np.uint8, np.uint16, np.uint32, np.uint64]


@pytest.mark.parametrize("dtype", INTEGER_DTYPES)
def test_integer_points_are_converted_to_float64(dtype):
    # numpy's habit: integer input to a floating-point computation is taken as float64.
    points = np.array([[0, 0, 0], [2, 0, 0], [0, 2, 0], [0, 0, 2], [2, 2, 2]])
    tetrahedra = [[0, 1, 2, 3], [1, 2, 3, 4]]
    x = np.array([[0, 0, 0], [3, 0, 0], [0, 2, 0], [0, 0, 2], [2, 3, 2]])
    field = fastcorot.ForceField(points.astype(dtype), tetrahedra, young_modulus=1000, poisson_ratio=0.3)
    reference = fastcorot.ForceField(points.astype(np.float64), tetrahedra, young_modulus=1000, poisson_ratio=0.3)
    assert field.dtype == np.float64
    force = field.add_force(x.astype(dtype))
    assert force.dtype == np.float64
    np.testing.assert_array_equal(force, reference.add_force(x.astype(np.float64)))
    np.testing.assert_array_equal(field.add_dforce(x.astype(dtype)), reference.add_dforce(x.astype(np.float64)))
    assert field.potential_energy(x.astype(dtype)) == reference.potential_energy(x.astype(np.float64))


def test_integer_positions_take_a_float32_fields_dtype():
    points = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], np.float32)
    field = fastcorot.ForceField(points, [[0, 1, 2, 3]])
    x = np.array([[0, 0, 0], [2, 0, 0], [0, 1, 0], [0, 0, 1]], np.int32)
    force = field.add_force(x)
    assert force.dtype == np.float32
    np.testing.assert_array_equal(force, field.add_force(x.astype(np.float32)))


@pytest.mark.parametrize("dtype", INTEGER_DTYPES)
def test_indices_of_any_integer_dtype(dtype):
    points, tetrahedra, x = small_mesh()
    reference = fastcorot.ForceField(points, tetrahedra).add_force(x)
    given = np.asarray(tetrahedra).astype(dtype)
    np.testing.assert_array_equal(fastcorot.ForceField(points, given).add_force(x), reference)
    edges = fastcorot.ForceField(points, tetrahedra).edges
    np.testing.assert_array_equal(
        fastcorot.ForceField(points, tetrahedra, edges=np.asarray(edges).astype(dtype)).add_force(x), reference)


def test_indices_beyond_the_index_range_are_refused():
    points, tetrahedra, x = small_mesh()
    huge = np.asarray(tetrahedra).astype(np.uint64)
    huge[0, 0] = np.uint64(2**63 + 5)
    with pytest.raises(ValueError, match=r"tetrahedra\[0\] has index"):
        fastcorot.ForceField(points, huge)
