// MechanicalSystem across topological changes: tetrahedral masses follow the mesh as SOFA's
// DiagonalMass and MeshMatrixMass do (equal to masses computed afresh from the new mesh), points
// left without tetrahedra and mass are held still (and let go when a tetrahedron comes back), and
// a failed addition changes nothing.
#include "fastcorot/fem/corotational_force_field.h"
#include "fastcorot/sim/mechanical_system.h"

#include "fastcorot/core/error.h"
#include "fastcorot/topology/regular_grid.h"
#include "support/finite_difference.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace fastcorot {
namespace {

using testing::relative_error;

struct Beam {
  std::shared_ptr<TetMesh> mesh;
  std::vector<Vec3<double>> rest;
};

Beam beam() {
  RegularGrid grid;
  grid.n = {6, 3, 3};
  grid.min = Vec3<double>(0, 0, 0);
  grid.max = Vec3<double>(5, 1, 1);
  return {std::make_shared<TetMesh>(grid.num_points(), grid_tetrahedra(grid, true)), grid_points<double>(grid)};
}

MechanicalSystem<double> system_on(const Beam& b, bool lumped, double density) {
  MechanicalSystem<double> system;
  system.state.position = b.rest;
  CorotationalForceField<double>::Parameters p;
  p.young_modulus = {1000.0};
  p.poisson_ratio = {0.3};
  system.force_fields.push_back(std::make_shared<CorotationalForceField<double>>(b.mesh, b.rest, p));
  if (lumped) {
    system.mass = Mass<double>::lumped(tetrahedral_lumped_masses<double>(*b.mesh, b.rest, density));
  } else {
    system.mass = Mass<double>::consistent(tetrahedral_mass_matrix<double>(*b.mesh, b.rest, density));
  }
  system.mass.follow_tetrahedra(b.mesh, density);
  system.finalize();
  return system;
}

Eigen::MatrixXd mass_matrix(const Mass<double>& mass, Index n) {
  TripletSink<double> sink;
  mass.add_to_matrix(sink, 1.0);
  return Eigen::MatrixXd(sink.to_sparse(3 * n));
}

// The tetrahedra at the x = 0 end (cell 0: the first 6 of the grid's 6 per cell, 2×2 cells per
// x-slab → cells 0, 5, 10, 15 hold x in [0, 1]).
std::vector<Index> first_slab(const TetMesh& mesh, const std::vector<Vec3<double>>& rest) {
  std::vector<Index> slab;
  for (Index t = 0; t < mesh.num_tetrahedra(); ++t) {
    double x = 0;
    for (Index v : mesh.tetrahedron(t)) x += rest[static_cast<std::size_t>(v)].x() / 4;
    if (x < 1) slab.push_back(t);
  }
  return slab;
}

TEST(SystemTopology, LumpedAndConsistentMassesFollowTheMesh) {
  for (bool lumped : {true, false}) {
    SCOPED_TRACE(lumped ? "lumped" : "consistent");
    const Beam b = beam();
    MechanicalSystem<double> system = system_on(b, lumped, 3.0);
    const std::vector<Index> slab = first_slab(*b.mesh, b.rest);
    ASSERT_EQ(slab.size(), 24u);
    const TopologyChange change = system.remove_tetrahedra(*b.mesh, slab);
    const Index n = system.size();
    const Mass<double> fresh = lumped ? Mass<double>::lumped(tetrahedral_lumped_masses<double>(*b.mesh, b.rest, 3.0))
                                      : Mass<double>::consistent(tetrahedral_mass_matrix<double>(*b.mesh, b.rest, 3.0));
    EXPECT_LT(relative_error(mass_matrix(system.mass, n), mass_matrix(fresh, n)), 1e-14);
    // The 9 points of the x = 0 face lost every tetrahedron: exactly zero mass, held still.
    ASSERT_EQ(change.isolated_points.size(), 9u);
    EXPECT_EQ(system.isolated, change.isolated_points);
    for (Index v : change.isolated_points) {
      EXPECT_EQ(system.mass.vertex_masses()[static_cast<std::size_t>(v)], 0.0);
      EXPECT_EQ(b.rest[static_cast<std::size_t>(v)].x(), 0.0);
    }
    std::vector<Vec3<double>> v(static_cast<std::size_t>(n), Vec3<double>::Ones());
    system.project(v);
    for (Index p : change.isolated_points) EXPECT_EQ(v[static_cast<std::size_t>(p)], Vec3<double>::Zero());
    EXPECT_NEAR(system.mass.total_mass(), 3.0 * 4.0, 1e-12);  // density × the volume left (4 of 5 units)

    // Back again: the masses of the full mesh, and nothing held.
    std::vector<Tetrahedron> back(change.removed_tetrahedron_vertices);
    system.add_tetrahedra(*b.mesh, back);
    const Mass<double> whole = lumped ? Mass<double>::lumped(tetrahedral_lumped_masses<double>(*b.mesh, b.rest, 3.0))
                                      : Mass<double>::consistent(tetrahedral_mass_matrix<double>(*b.mesh, b.rest, 3.0));
    EXPECT_LT(relative_error(mass_matrix(system.mass, n), mass_matrix(whole, n)), 1e-14);
    EXPECT_TRUE(system.isolated.empty());
  }
}

TEST(SystemTopology, AssembledMatrixHoldsIsolatedPointsLikeFixedOnes) {
  const Beam b = beam();
  MechanicalSystem<double> system = system_on(b, true, 1.0);
  system.remove_tetrahedra(*b.mesh, first_slab(*b.mesh, b.rest));
  const MatrixFactors<double> factors{1.0, 0.0, -0.01};
  const Eigen::MatrixXd a = Eigen::MatrixXd(system.assemble(factors));
  for (Index v : system.isolated) {
    for (Index c = 0; c < 3; ++c) {
      const Index row = 3 * v + c;
      EXPECT_EQ(a.row(row).cwiseAbs().sum(), 1.0);
      EXPECT_EQ(a(row, row), 1.0);
    }
  }
  // The product agrees with the assembled matrix on everything else.
  std::vector<Vec3<double>> dx(static_cast<std::size_t>(system.size())), out(dx.size());
  for (std::size_t i = 0; i < dx.size(); ++i) dx[i] = Vec3<double>(0.1 * static_cast<double>(i), 1.0, -0.5);
  system.multiply(factors, dx, out);
  system.project(dx);
  Eigen::VectorXd flat_dx(3 * static_cast<Eigen::Index>(dx.size())), flat_out(flat_dx.size());
  for (std::size_t i = 0; i < dx.size(); ++i) {
    flat_dx.segment<3>(3 * static_cast<Eigen::Index>(i)) = dx[i];
    flat_out.segment<3>(3 * static_cast<Eigen::Index>(i)) = out[i];
  }
  Eigen::VectorXd expected = a * flat_dx;
  for (Index v : system.isolated) expected.segment<3>(3 * v).setZero();
  for (Index v : system.fixed) expected.segment<3>(3 * v).setZero();
  EXPECT_LT(relative_error(flat_out, expected), 1e-13);
}

TEST(SystemTopology, AFailedAdditionChangesNothing) {
  const Beam b = beam();
  MechanicalSystem<double> system = system_on(b, true, 1.0);
  const Index tets = b.mesh->num_tetrahedra();
  const double mass = system.mass.total_mass();
  // Points 0, 1, 2 lie on the x axis: any tetrahedron on them is flat.
  EXPECT_THROW(system.add_tetrahedra(*b.mesh, std::vector<Tetrahedron>{{0, 1, 2, 20}}), Error);
  EXPECT_THROW(system.add_tetrahedra(*b.mesh, std::vector<Tetrahedron>{{0, 1, 7, 5000}}), Error);
  EXPECT_THROW(system.remove_tetrahedra(*b.mesh, std::vector<Index>{tets}), Error);
  EXPECT_EQ(b.mesh->num_tetrahedra(), tets);
  EXPECT_EQ(system.mass.total_mass(), mass);
}

}  // namespace
}  // namespace fastcorot
