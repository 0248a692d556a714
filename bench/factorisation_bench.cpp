// The sparse direct solver's kernels on implicit Euler's matrix of a bent beam (BlockLDLT, the
// 3×3-block LDLᵀ) beside Eigen's scalar SimplicialLDLT on the same matrix: numeric factorisation,
// one solve, and the compliance Cᵀ A⁻¹ C of constraint-like columns (three unit rows per point of
// the fixed end face, as a FixedLagrangianConstraint makes them). Beams: 25×5×5 (the size of
// SOFA's FixedLagrangianConstaint_Vec3) and 40×10×10.
//   build-release/bench/fastcorot_bench_factorisation --benchmark_filter=25x5x5
#include "beams.h"

#include "fastcorot/sim/block_ldlt.h"
#include "fastcorot/sim/mass.h"
#include "fastcorot/sim/mechanical_system.h"

#include <Eigen/SparseCholesky>

namespace fastcorot::bench {
namespace {

struct Problem {
  Eigen::SparseMatrix<double> matrix;
  Eigen::SparseMatrix<double> columns;
};

Problem problem(std::array<Index, 3> n) {
  const Beam beam{"", n};
  BeamField<double> b = make_beam_field<double>(beam, RotationMethod::qr, 1);
  MechanicalSystem<double> system;
  system.state.position = b.x;
  system.state.rest_position = b.rest;
  system.force_fields.push_back(std::shared_ptr<ForceField<double>>(std::move(b.field)));
  system.mass = Mass<double>::lumped(std::vector<double>(b.rest.size(), 1.0 / static_cast<double>(b.rest.size())));
  system.finalize();
  std::vector<Vec3<double>> f(b.rest.size());
  system.compute_force(system.state.position, f);  // linearise at the bent state
  const double h = 0.01;
  Problem p;
  p.matrix = system.assemble(MatrixFactors<double>{1 + h * 0.1, -h, -h * (h + 0.1)});
  p.matrix.makeCompressed();
  std::vector<Eigen::Triplet<double>> entries;
  Index column = 0;
  for (Index k = 0; k < n[2]; ++k) {
    for (Index j = 0; j < n[1]; ++j) {
      const Index point = n[0] * (j + n[1] * k);  // x = 0 face
      for (Index axis = 0; axis < 3; ++axis) entries.emplace_back(3 * point + axis, column++, 1.0);
    }
  }
  p.columns.resize(p.matrix.rows(), column);
  p.columns.setFromTriplets(entries.begin(), entries.end());
  return p;
}

void register_all() {
  for (const auto& n : {std::array<Index, 3>{25, 5, 5}, std::array<Index, 3>{40, 10, 10}}) {
    const std::string name = std::to_string(n[0]) + "x" + std::to_string(n[1]) + "x" + std::to_string(n[2]);
    benchmark::RegisterBenchmark(("factorise/" + name + "/block_ldlt").c_str(), [n](benchmark::State& state) {
      const Problem p = problem(n);
      BlockLDLT<double> ldlt;
      ldlt.analyse(p.matrix);
      for (auto _ : state) benchmark::DoNotOptimize(ldlt.factorise(p.matrix));
    });
    benchmark::RegisterBenchmark(("factorise/" + name + "/eigen_simplicial_ldlt").c_str(), [n](benchmark::State& state) {
      const Problem p = problem(n);
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
      ldlt.analyzePattern(p.matrix);
      for (auto _ : state) ldlt.factorize(p.matrix);
    });
    benchmark::RegisterBenchmark(("solve/" + name + "/block_ldlt").c_str(), [n](benchmark::State& state) {
      const Problem p = problem(n);
      BlockLDLT<double> ldlt;
      ldlt.analyse(p.matrix);
      ldlt.factorise(p.matrix);
      const Eigen::VectorXd b = Eigen::VectorXd::Ones(p.matrix.rows());
      Eigen::VectorXd x(p.matrix.rows());
      for (auto _ : state) ldlt.solve(b.data(), x.data());
    });
    benchmark::RegisterBenchmark(("solve/" + name + "/eigen_simplicial_ldlt").c_str(), [n](benchmark::State& state) {
      const Problem p = problem(n);
      Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(p.matrix);
      const Eigen::VectorXd b = Eigen::VectorXd::Ones(p.matrix.rows());
      Eigen::VectorXd x(p.matrix.rows());
      for (auto _ : state) benchmark::DoNotOptimize(x = ldlt.solve(b));
    });
    benchmark::RegisterBenchmark(("compliance/" + name + "/block_ldlt").c_str(), [n](benchmark::State& state) {
      const Problem p = problem(n);
      BlockLDLT<double> ldlt;
      ldlt.analyse(p.matrix);
      ldlt.factorise(p.matrix);
      for (auto _ : state) benchmark::DoNotOptimize(ldlt.compliance(p.columns, 1));
      state.counters["rows"] = static_cast<double>(p.columns.cols());
    });
  }
}

}  // namespace
}  // namespace fastcorot::bench

int main(int argc, char** argv) {
  fastcorot::bench::register_all();
  return fastcorot::bench::run_registered_benchmarks(argc, argv);
}
