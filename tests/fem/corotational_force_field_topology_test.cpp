// The force field across topological changes (corotational_force_field_topology.cpp): after every
// removal or addition it must compute what a force field built from scratch on the same mesh
// computes (forces, df = K dx, the assembled stiffness, edge blocks), for each method, in float and
// double, also when the edge blocks are read before the next add_force (they must then be the
// linearisation at the last positions, not stale ones); one and two threads bitwise alike; and
// removing then re-adding the same tetrahedra must give back the same forces and stiffness.
#include "fastcorot/fem/corotational_force_field.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"
#include "support/deformations.h"
#include "support/finite_difference.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace fastcorot {
namespace {

using testing::relative_error;

template <class Real>
using Points = std::vector<Vec3<Real>>;

template <class Real>
Points<Real> cast(const std::vector<Vec3<double>>& points) {
  Points<Real> result;
  for (const auto& p : points) result.push_back(p.cast<Real>());
  return result;
}

template <class Real>
Eigen::VectorXd flat(const Points<Real>& points) {
  Eigen::VectorXd v(3 * static_cast<Eigen::Index>(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) v.segment<3>(3 * static_cast<Eigen::Index>(i)) = points[i].template cast<double>();
  return v;
}

struct Grid {
  Index num_points;
  std::vector<Tetrahedron> tetrahedra;
  std::vector<Vec3<double>> rest;
};

// 20×6×6 points: two schedule parts, so changes meet several groups and phases.
Grid beam() {
  RegularGrid grid;
  grid.n = {20, 6, 6};
  grid.min = Vec3<double>(0, 0, 0);
  grid.max = Vec3<double>(4, 1, 1.2);
  return {grid.num_points(), grid_tetrahedra(grid, true), grid_points<double>(grid)};
}

// The beam with its points and tetrahedra in a random order: the force field renumbers its points.
Grid shuffled_beam() {
  Grid grid = beam();
  std::mt19937 rng(5);
  std::vector<Index> point(static_cast<std::size_t>(grid.num_points));
  std::iota(point.begin(), point.end(), Index(0));
  std::shuffle(point.begin(), point.end(), rng);
  std::vector<Vec3<double>> rest(grid.rest.size());
  for (std::size_t i = 0; i < rest.size(); ++i) rest[static_cast<std::size_t>(point[i])] = grid.rest[i];
  grid.rest = rest;
  for (Tetrahedron& tet : grid.tetrahedra) {
    for (Index& v : tet) v = point[static_cast<std::size_t>(v)];
  }
  std::shuffle(grid.tetrahedra.begin(), grid.tetrahedra.end(), rng);
  return grid;
}

template <class Real>
typename CorotationalForceField<Real>::Parameters parameters(RotationMethod method) {
  typename CorotationalForceField<Real>::Parameters p;
  p.young_modulus = {Real(2000)};
  p.poisson_ratio = {Real(0.3)};
  p.method = method;
  return p;
}

template <class Real>
struct Outputs {
  Points<Real> force, dforce;
  Eigen::SparseMatrix<double> stiffness;
};

// max |a - b| / max |b| over the entries of two sparse matrices.
double sparse_relative_error(const Eigen::SparseMatrix<double>& a, const Eigen::SparseMatrix<double>& b) {
  const Eigen::SparseMatrix<double> difference = a - b;
  double largest = 0, scale = 1e-300;
  for (int k = 0; k < difference.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(difference, k); it; ++it) largest = std::max(largest, std::abs(it.value()));
  }
  for (int k = 0; k < b.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(b, k); it; ++it) scale = std::max(scale, std::abs(it.value()));
  }
  return largest / scale;
}

// The field's outputs at x; with `refresh_first` = false the stiffness and dforce are read before
// add_force (the linearisation of the last add_force, whatever changed since).
template <class Real>
Outputs<Real> outputs(CorotationalForceField<Real>& field, const Points<Real>& x, const Points<Real>& dx,
                      bool refresh_first = true) {
  Outputs<Real> out;
  out.force.assign(x.size(), Vec3<Real>::Zero());
  out.dforce.assign(x.size(), Vec3<Real>::Zero());
  if (!refresh_first) {
    field.add_dforce(dx, out.dforce, Real(1));
    out.stiffness = field.stiffness_matrix().template cast<double>();
  }
  field.add_force(x, out.force);
  if (refresh_first) {
    field.add_dforce(dx, out.dforce, Real(1));
    out.stiffness = field.stiffness_matrix().template cast<double>();
  }
  return out;
}

template <class Real>
void expect_close(const Outputs<Real>& a, const Outputs<Real>& b, double tolerance, const char* what) {
  EXPECT_LT(relative_error(flat(a.force), flat(b.force)), tolerance) << what << ": force";
  EXPECT_LT(relative_error(flat(a.dforce), flat(b.dforce)), tolerance) << what << ": dforce";
  EXPECT_LT(sparse_relative_error(a.stiffness, b.stiffness), tolerance) << what << ": stiffness";
}

// A field built from scratch on `mesh`'s current tetrahedra (and, with `same_edges`, its edge list,
// so that edge indices match).
template <class Real>
CorotationalForceField<Real> fresh_on(const TetMesh& mesh, const Points<Real>& rest,
                                      const typename CorotationalForceField<Real>::Parameters& p, bool same_edges = false) {
  std::vector<Tetrahedron> tets(mesh.tetrahedra().begin(), mesh.tetrahedra().end());
  auto copy = same_edges ? std::make_shared<TetMesh>(mesh.num_points(), tets, std::vector<Edge>(mesh.edges().begin(), mesh.edges().end()))
                         : std::make_shared<TetMesh>(mesh.num_points(), tets);
  return CorotationalForceField<Real>(copy, rest, p);
}

// The beam in double with a deformed state x and a direction dx, and a qr field on it.
struct BeamCase {
  Grid grid = beam();
  Points<double> x, dx;
  std::shared_ptr<TetMesh> mesh;
  std::unique_ptr<CorotationalForceField<double>> field;

  explicit BeamCase(unsigned seed, typename CorotationalForceField<double>::Parameters p = parameters<double>(RotationMethod::qr)) {
    std::mt19937 rng(seed);
    x = testing::perturbed(grid.rest, 0.05, rng);
    dx = testing::perturbed(Points<double>(grid.rest.size(), Vec3<double>::Zero()), 0.01, rng);
    mesh = std::make_shared<TetMesh>(grid.num_points, grid.tetrahedra);
    field = std::make_unique<CorotationalForceField<double>>(mesh, grid.rest, p);
  }
};

template <class Real>
void random_changes_equal_a_fresh_field(RotationMethod method, double tolerance, const Grid& grid = beam(),
                                        bool renumbered = false) {
  const Points<Real> rest = cast<Real>(grid.rest);
  std::mt19937 rng(21);
  const Points<Real> x = cast<Real>(testing::perturbed(grid.rest, 0.04, rng));
  const Points<Real> x2 = cast<Real>(testing::perturbed(grid.rest, 0.04, rng));
  const Points<Real> dx = cast<Real>(testing::perturbed(std::vector<Vec3<double>>(grid.rest.size(), Vec3<double>::Zero()), 0.01, rng));
  auto mesh_one = std::make_shared<TetMesh>(grid.num_points, grid.tetrahedra);
  auto mesh_two = std::make_shared<TetMesh>(grid.num_points, grid.tetrahedra);
  CorotationalForceField<Real> one(mesh_one, rest, parameters<Real>(method));
  CorotationalForceField<Real> two(mesh_two, rest, parameters<Real>(method));
  two.set_threads(2);
  EXPECT_EQ(one.renumbers_points(), renumbered);
  std::vector<Tetrahedron> pool;
  for (int round = 0; round < 12; ++round) {
    // Linearise at x2 first, so that a change must not leave blocks of another state behind.
    Points<Real> scratch(rest.size(), Vec3<Real>::Zero());
    one.add_force(x2, scratch);
    two.add_force(x2, scratch);
    const int kind = round % 4;
    std::vector<Tetrahedron> added;
    if (kind == 3 && !pool.empty()) {
      // Back some removed tetrahedra, plus new ones across the beam (new edges, serial group).
      std::shuffle(pool.begin(), pool.end(), rng);
      const std::size_t count = std::min<std::size_t>(pool.size(), 40);
      added.assign(pool.end() - static_cast<std::ptrdiff_t>(count), pool.end());
      pool.resize(pool.size() - count);
      while (added.size() < count + 5) {
        Tetrahedron t;
        for (Index& v : t) v = static_cast<Index>(rng() % static_cast<unsigned>(grid.num_points));
        try {
          one.check_new_tetrahedra(std::vector<Tetrahedron>{t});
          added.push_back(t);
        } catch (const Error&) {
        }
      }
      one.add_tetrahedra(added);
      two.add_tetrahedra(added);
    } else {
      std::vector<Index> indices(static_cast<std::size_t>(mesh_one->num_tetrahedra()));
      std::iota(indices.begin(), indices.end(), Index(0));
      std::shuffle(indices.begin(), indices.end(), rng);
      indices.resize(60);
      for (Index t : indices) pool.push_back(mesh_one->tetrahedron(t));
      one.remove_tetrahedra(indices);
      two.remove_tetrahedra(indices);
    }
    ASSERT_EQ(mesh_one->num_tetrahedra(), mesh_two->num_tetrahedra());
    // Blocks read before the next add_force: the linearisation at x2 of the new mesh.
    CorotationalForceField<Real> fresh = fresh_on(*mesh_one, rest, parameters<Real>(method), true);
    Points<Real> fresh_scratch(rest.size(), Vec3<Real>::Zero());
    fresh.add_force(x2, fresh_scratch);
    const Outputs<Real> stale_check = outputs(one, x, dx, false);
    const Outputs<Real> reference_at_x2 = outputs(fresh, x, dx, false);
    EXPECT_LT(relative_error(flat(stale_check.dforce), flat(reference_at_x2.dforce)), tolerance) << "round " << round;
    EXPECT_LT(sparse_relative_error(stale_check.stiffness, reference_at_x2.stiffness), tolerance) << "round " << round;
    // And after add_force at x.
    const Outputs<Real> a = outputs(one, x, dx), reference = outputs(fresh, x, dx);
    expect_close(a, reference, tolerance, "after a change");
    const auto blocks = one.edge_stiffness(), fresh_blocks = fresh.edge_stiffness();
    ASSERT_EQ(blocks.size(), fresh_blocks.size());
    double largest = 0, worst = 0;
    for (std::size_t e = 0; e < blocks.size(); ++e) {
      largest = std::max(largest, static_cast<double>(fresh_blocks[e].cwiseAbs().maxCoeff()));
      worst = std::max(worst, static_cast<double>((blocks[e] - fresh_blocks[e]).cwiseAbs().maxCoeff()));
    }
    EXPECT_LT(worst, tolerance * largest) << "edge blocks, round " << round;
    // Two threads: bitwise the same as one.
    const Outputs<Real> b = outputs(two, x, dx);
    EXPECT_EQ(flat(a.force), flat(b.force)) << "round " << round;
    EXPECT_EQ(flat(a.dforce), flat(b.dforce)) << "round " << round;
    EXPECT_EQ(sparse_relative_error(a.stiffness, b.stiffness), 0.0) << "round " << round;
  }
}

TEST(ForceFieldTopology, RandomChangesEqualAFreshFieldDouble) {
  for (RotationMethod method : {RotationMethod::qr, RotationMethod::polar, RotationMethod::polar2, RotationMethod::none}) {
    SCOPED_TRACE(static_cast<int>(method));
    random_changes_equal_a_fresh_field<double>(method, 1e-12);
  }
}

TEST(ForceFieldTopology, RandomChangesEqualAFreshFieldFloat) {
  for (RotationMethod method : {RotationMethod::qr, RotationMethod::polar2}) {
    SCOPED_TRACE(static_cast<int>(method));
    random_changes_equal_a_fresh_field<float>(method, 2e-5);
  }
}

TEST(ForceFieldTopology, RandomChangesOnAShuffledMeshEqualAFreshField) {
  // The force field keeps its own point order; changes follow it.
  for (RotationMethod method : {RotationMethod::qr, RotationMethod::polar}) {
    SCOPED_TRACE(static_cast<int>(method));
    random_changes_equal_a_fresh_field<double>(method, 1e-12, shuffled_beam(), true);
  }
}

TEST(ForceFieldTopology, RemovingThenReaddingRestoresForcesAndStiffness) {
  BeamCase s(5);
  const auto& [grid, x, dx, mesh, owned] = s;
  CorotationalForceField<double>& field = *owned;
  const Outputs<double> before = outputs(field, x, dx);
  // A slab through the middle of the beam (a cut), then all of it back.
  std::vector<Index> slab;
  std::vector<Tetrahedron> slab_tets;
  for (Index t = 0; t < mesh->num_tetrahedra(); ++t) {
    const Tetrahedron& tet = mesh->tetrahedron(t);
    double cx = 0;
    for (Index v : tet) cx += grid.rest[static_cast<std::size_t>(v)].x() / 4;
    if (std::abs(cx - 2.0) < 0.15) {
      slab.push_back(t);
      slab_tets.push_back(tet);
    }
  }
  ASSERT_GT(slab.size(), 50u);
  field.remove_tetrahedra(slab);
  const Outputs<double> cut = outputs(field, x, dx);
  EXPECT_GT(relative_error(flat(cut.force), flat(before.force)), 1e-3);  // the cut changes the forces
  field.add_tetrahedra(slab_tets);
  const Outputs<double> after = outputs(field, x, dx);
  // Same tetrahedra, other order: the same forces and stiffness up to the order of the sums.
  expect_close(after, before, 1e-13, "removed and re-added");
}

TEST(ForceFieldTopology, ManyAdditionsRebuildTheSchedules) {
  // Tetrahedra added on top of a full mesh find no room in their groups and go to the serial group;
  // past a threshold everything is rebuilt. Both must give what a fresh field gives.
  BeamCase s(9);
  const auto& [grid, x, dx, mesh, owned] = s;
  CorotationalForceField<double>& field = *owned;
  for (std::size_t count : {10u, 1500u}) {
    const std::vector<Tetrahedron> extra(grid.tetrahedra.begin(), grid.tetrahedra.begin() + static_cast<std::ptrdiff_t>(count));
    field.add_tetrahedra(extra);
    CorotationalForceField<double> fresh = fresh_on(*mesh, grid.rest, parameters<double>(RotationMethod::qr));
    expect_close(outputs(field, x, dx), outputs(fresh, x, dx), 1e-12, "after additions");
  }
}

TEST(ForceFieldTopology, PerTetrahedronMaterialsFollowTheirTetrahedra) {
  auto p = parameters<double>(RotationMethod::qr);
  p.young_modulus.clear();
  const std::size_t n = beam().tetrahedra.size();
  for (std::size_t t = 0; t < n; ++t) p.young_modulus.push_back(1000.0 + static_cast<double>(t));
  BeamCase s(3, p);
  const auto& [grid, x, dx, mesh, owned] = s;
  CorotationalForceField<double>& field = *owned;
  const std::vector<Index> removed = {5, 700, 2849, 17};
  const TopologyChange change = field.remove_tetrahedra(removed);
  const std::vector<Index> map = old_to_new(static_cast<Index>(n), change.tetrahedron_moves);
  for (std::size_t t = 0; t < n; ++t) {
    if (map[t] >= 0) {
      ASSERT_EQ(field.parameters().young_modulus[static_cast<std::size_t>(map[t])], 1000.0 + static_cast<double>(t));
    }
  }
  CorotationalForceField<double> fresh = fresh_on(*mesh, grid.rest, field.parameters());
  expect_close(outputs(field, x, dx), outputs(fresh, x, dx), 1e-12, "per-tetrahedron E");
}

TEST(ForceFieldTopology, AnEmptiedFieldAddsNothing) {
  BeamCase s(4, parameters<double>(RotationMethod::qr));
  const auto& [grid, x, dx, mesh, owned] = s;
  CorotationalForceField<double>& field = *owned;
  std::vector<Index> all(grid.tetrahedra.size());
  std::iota(all.begin(), all.end(), Index(0));
  field.remove_tetrahedra(all);
  ASSERT_EQ(mesh->num_tetrahedra(), 0);
  const Vec3<double> marker(1.5, -2.0, 0.25);
  std::vector<Vec3<double>> f(x.size(), marker), df(x.size(), marker);
  field.add_force(x, f);
  field.add_dforce(dx, df, -0.3);
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_EQ(f[i], marker) << "point " << i;
    EXPECT_EQ(df[i], marker) << "point " << i;
  }
  EXPECT_EQ(field.stiffness_matrix(1.0).nonZeros(), 0);
}

TEST(ForceFieldTopology, PerTetrahedronListsSurviveRemovingEverythingAndAddingBack) {
  // Removing every tetrahedron empties a per-tetrahedron list; tetrahedra added afterwards take
  // entry 0 of the list given at construction (not a value of an empty list), and a list shrunk to
  // one entry still follows its tetrahedron rather than becoming a value for all.
  auto p = parameters<double>(RotationMethod::qr);
  const std::size_t n = beam().tetrahedra.size();
  p.young_modulus.clear();
  for (std::size_t t = 0; t < n; ++t) p.young_modulus.push_back(1000.0 + static_cast<double>(t));
  BeamCase s(4, p);
  const auto& [grid, x, dx, mesh, owned] = s;
  CorotationalForceField<double>& field = *owned;
  std::vector<Index> all_but_7(n);
  std::iota(all_but_7.begin(), all_but_7.end(), Index(0));
  all_but_7.erase(all_but_7.begin() + 7);
  field.remove_tetrahedra(all_but_7);
  EXPECT_EQ(field.parameters().young_modulus, std::vector<double>{1007.0});
  field.remove_tetrahedra(std::vector<Index>{0});
  EXPECT_TRUE(field.parameters().young_modulus.empty());
  field.add_tetrahedra(std::vector<Tetrahedron>(grid.tetrahedra.begin(), grid.tetrahedra.begin() + 3));
  EXPECT_EQ(field.parameters().young_modulus, (std::vector<double>{1000.0, 1000.0, 1000.0}));
  auto uniform = parameters<double>(RotationMethod::qr);
  uniform.young_modulus = {1000.0};
  CorotationalForceField<double> fresh = fresh_on(*mesh, grid.rest, uniform);
  expect_close(outputs(field, x, dx), outputs(fresh, x, dx), 1e-12, "after emptying");
}

TEST(ForceFieldTopology, BadChangesAreErrorsAndChangeNothing) {
  const Grid grid = beam();
  auto mesh = std::make_shared<TetMesh>(grid.num_points, grid.tetrahedra);
  CorotationalForceField<double> field(mesh, grid.rest, parameters<double>(RotationMethod::qr));
  const Index n = mesh->num_tetrahedra();
  EXPECT_THROW(field.remove_tetrahedra(std::vector<Index>{0, n}), Error);
  EXPECT_THROW(field.add_tetrahedra(std::vector<Tetrahedron>{{0, 1, 2, grid.num_points}}), Error);
  // Points 0, 1, 2, 3 of the grid lie on one line: zero volume.
  try {
    field.add_tetrahedra(std::vector<Tetrahedron>{{0, 1, 2, 3}});
    ADD_FAILURE() << "a flat tetrahedron was accepted";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("degenerate"), std::string::npos) << error.what();
  }
  EXPECT_EQ(mesh->num_tetrahedra(), n);
}

}  // namespace
}  // namespace fastcorot
