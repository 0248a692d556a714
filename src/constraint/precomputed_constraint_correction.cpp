#include "fastcorot/constraint/precomputed_constraint_correction.h"

#include "fastcorot/constraint/free_motion_animation_loop.h"
#include "fastcorot/core/error.h"
#include "fastcorot/core/parallel.h"
#include "fastcorot/sim/rotation_finder.h"
#include "fastcorot/sim/sparse_factorisation.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace fastcorot {

void check_precomputed_compliance_size(const std::string& where, std::size_t points) {
  const double rows = 3.0 * static_cast<double>(points);
  const double bytes = rows * rows * sizeof(double);
  if (bytes > static_cast<double>(kMaxPrecomputedComplianceBytes)) {
    throw make_error(where, ": the precomputed compliance of ", points, " points is a dense ", 3 * points, " × ", 3 * points,
                     " matrix of ", bytes / double(1 << 30), " GiB, more than the ", kMaxPrecomputedComplianceBytes >> 30,
                     " GiB allowed: use a LinearSolverConstraintCorrection (W through the sparse factorisation)");
  }
}

template <class Real>
DenseMatrix<Real> precompute_compliance(SimulatedObject<Real>& object, Real dt) {
  const std::string where = "PrecomputedConstraintCorrection of " + object.path;
  MechanicalSystem<Real>& system = object.system;
  if (system.rigids) throw make_error(where, ": the object holds rigid bodies (Rigid3): only points (Vec3) are supported");
  const auto factors = object.ode_solver->integration_factors(dt);
  if (!factors) {
    throw make_error(where, ": its ODE solver does not give SOFA's integration factors (SOFA needs an EulerImplicitSolver "
                     "for the precomputation)");
  }
  const auto n = static_cast<std::size_t>(system.size());
  check_precomputed_compliance_size(where, n);
  // SOFA steps once from rest at the start positions: the force fields linearised there.
  std::vector<Vec3<Real>> force(n), rest_velocity(n, Vec3<Real>::Zero());
  system.update_mass();
  system.compute_force(system.state.position, force, rest_velocity);
  SparseFactorisation<Real> factorisation;
  if (!factorisation.factorise(system.assemble(factors->matrix))) {
    throw make_error(where, ": the system matrix at the start is singular (a zero pivot): no compliance");
  }
  // Column j: a unit force on entry j is an impulse dt e_j, so Δv = A⁻¹ P dt e_j (projected like
  // SOFA's projectResponse), and SOFA stores (position / dt) Δv = position P A⁻¹ P e_j.
  const auto rows = static_cast<Index>(3 * n);
  DenseMatrix<Real> compliance(rows, rows);
  constexpr int kTasks = 64;
  const Index per_task = (rows + kTasks - 1) / kTasks;
  run_tasks(system.threads(), kTasks, [&](int task) {
    std::vector<Vec3<Real>> rhs(n), solution(n);
    const Index first = task * per_task;
    const Index end = std::min(rows, first + per_task);
    for (Index j = first; j < end; ++j) {
      std::fill(rhs.begin(), rhs.end(), Vec3<Real>::Zero());
      rhs[static_cast<std::size_t>(j / 3)][static_cast<int>(j % 3)] = 1;
      system.project(rhs);
      factorisation.solve(rhs.data()->data(), solution.data()->data(), rows);
      system.project(solution);
      for (Index i = 0; i < rows; ++i) {
        compliance(i, j) = factors->position * solution[static_cast<std::size_t>(i / 3)][static_cast<int>(i % 3)];
      }
    }
  });
  if (!compliance.allFinite()) throw make_error(where, ": the precomputed compliance is not finite");
  return compliance;
}

std::string compliance_file_name(const std::string& node_name, std::size_t rows, double dt) {
  std::ostringstream name;
  name << node_name << "-" << rows << "-" << dt << ".comp";
  return name.str();
}

template <class Real>
DenseMatrix<Real> read_compliance_file(const std::filesystem::path& file, std::size_t rows) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw make_error("compliance file ", file.string(), ": cannot be opened");
  in.seekg(0, std::ios::end);
  const auto bytes = static_cast<std::uint64_t>(in.tellg());
  const std::uint64_t expected = std::uint64_t(rows) * rows * sizeof(double);
  if (bytes != expected) {
    throw make_error("compliance file ", file.string(), ": holds ", bytes, " bytes, but a ", rows, " × ", rows,
                     " compliance (3 rows per point) of doubles is ", expected,
                     " bytes (a file for another object, another dt, or truncated: delete it or set recompute=\"1\")");
  }
  in.seekg(0);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> values(rows, rows);
  in.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(expected));
  if (!in) throw make_error("compliance file ", file.string(), ": read failed");
  if (!values.allFinite()) throw make_error("compliance file ", file.string(), ": holds values that are not finite");
  return values.template cast<Real>();
}

template <class Real>
void write_compliance_file(const std::filesystem::path& file, const DenseMatrix<Real>& compliance) {
  const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> values = compliance.template cast<double>();
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (out) out.write(reinterpret_cast<const char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(double)));
  if (!out) throw make_error("compliance file ", file.string(), ": cannot be written");
}

template <class Real>
PrecomputedConstraintCorrection<Real>::PrecomputedConstraintCorrection(std::string where, std::size_t object,
                                                                       std::shared_ptr<const DenseMatrix<Real>> compliance,
                                                                       Parameters parameters)
    : ConstraintCorrection<Real>(std::move(where), object), compliance_(std::move(compliance)), parameters_(parameters) {
  if (!compliance_ || compliance_->rows() != compliance_->cols() || compliance_->rows() % 3 != 0) {
    throw make_error(this->where(), ": the compliance is not a square matrix of 3 rows per point");
  }
  if (!compliance_->allFinite()) throw make_error(this->where(), ": the compliance is not finite");
  if (!(parameters_.regularization >= 0) || !std::isfinite(parameters_.regularization)) {
    throw make_error(this->where(), ": regularizationTerm = ", parameters_.regularization, ": must be a finite number >= 0");
  }
}

template <class Real>
void PrecomputedConstraintCorrection<Real>::check_size(const SimulatedObject<Real>& object) const {
  if (compliance_->rows() != 3 * static_cast<Index>(object.system.size())) {
    throw make_error(this->where(), ": the compliance has ", compliance_->rows(), " rows, but ", object.path, " has ",
                     object.system.size(), " points now (3 rows each): a precomputed compliance cannot follow topological changes");
  }
}

template <class Real>
const std::vector<Mat3<Real>>& PrecomputedConstraintCorrection<Real>::rotations(const SimulatedObject<Real>& object) {
  auto found = find_rotations(object.system, initial_rotations_);
  if (!found) {
    throw make_error(this->where(), ": rotations=\"1\" needs the point rotations of a TetrahedronFEMForceField or "
                     "HexahedronFEMForceField on ", object.path, " (SOFA's RotationFinder)");
  }
  rotations_ = std::move(*found);
  return rotations_;
}

template <class Real>
void PrecomputedConstraintCorrection<Real>::add_compliance(SimulatedObject<Real>& object, const Eigen::SparseMatrix<Real>& ht,
                                                           ConstraintOrder order, Real dt, DenseMatrix<Real>& w) {
  check_size(object);
  const Real factor = order == ConstraintOrder::velocity ? Real(1) / dt : Real(1);
  const auto points = static_cast<std::size_t>(object.system.size());
  // The rows reaching the object, the points they touch (SOFA's active dofs), and per row the
  // number of points it touches (SOFA adds the regularisation once per point).
  std::vector<Index> columns, touches;
  std::vector<Index> slot(points, -1);
  support_.clear();
  for (Index c = 0; c < static_cast<Index>(ht.cols()); ++c) {
    std::vector<Index> touched;
    for (typename Eigen::SparseMatrix<Real>::InnerIterator it(ht, c); it; ++it) {
      if (it.value() == 0) continue;
      const Index block = static_cast<Index>(it.row()) / 3;
      if (std::find(touched.begin(), touched.end(), block) == touched.end()) touched.push_back(block);
      if (slot[static_cast<std::size_t>(block)] < 0) {
        slot[static_cast<std::size_t>(block)] = static_cast<Index>(support_.size());
        support_.push_back(block);
      }
    }
    if (touched.empty()) continue;
    columns.push_back(c);
    touches.push_back(static_cast<Index>(touched.size()));
  }
  if (columns.empty()) return;
  const auto s = static_cast<Index>(support_.size());
  const auto r = static_cast<Index>(columns.size());
  // Hᵀ on the support, dense (3s × r); with rotations, each point's blocks into its start frame.
  DenseMatrix<Real> h = DenseMatrix<Real>::Zero(3 * s, r);
  for (Index k = 0; k < r; ++k) {
    for (typename Eigen::SparseMatrix<Real>::InnerIterator it(ht, columns[static_cast<std::size_t>(k)]); it; ++it) {
      const Index block = static_cast<Index>(it.row()) / 3;
      h(3 * slot[static_cast<std::size_t>(block)] + static_cast<Index>(it.row()) % 3, k) = it.value();
    }
  }
  if (parameters_.rotations == Rotations::both) {
    const auto& turn = rotations(object);
    for (Index j = 0; j < s; ++j) {
      h.middleRows(3 * j, 3) = (turn[static_cast<std::size_t>(support_[static_cast<std::size_t>(j)])].transpose() *
                                h.middleRows(3 * j, 3)).eval();
    }
  }
  DenseMatrix<Real> c(3 * s, 3 * s);
  for (Index a = 0; a < s; ++a) {
    for (Index b = 0; b < s; ++b) {
      c.template block<3, 3>(3 * a, 3 * b) =
          compliance_->template block<3, 3>(3 * support_[static_cast<std::size_t>(a)], 3 * support_[static_cast<std::size_t>(b)]);
    }
  }
  const DenseMatrix<Real> block = factor * (h.transpose() * (c * h));
  for (Index a = 0; a < r; ++a) {
    for (Index b = 0; b < r; ++b) w(columns[static_cast<std::size_t>(a)], columns[static_cast<std::size_t>(b)]) += block(a, b);
    w(columns[static_cast<std::size_t>(a)], columns[static_cast<std::size_t>(a)]) +=
        parameters_.regularization * static_cast<Real>(touches[static_cast<std::size_t>(a)]);
  }
}

template <class Real>
void PrecomputedConstraintCorrection<Real>::correct(SimulatedObject<Real>& object, std::span<const Vec3<Real>> impulse,
                                                    ConstraintOrder order, Real dt) {
  check_size(object);
  const std::size_t n = impulse.size();
  const std::vector<Mat3<Real>>* turn = parameters_.rotations != Rotations::none ? &rotations(object) : nullptr;
  const bool into_start_frame = parameters_.rotations == Rotations::both;
  // Hᵀλ on the points it reaches (in their start frames with both rotations).
  support_.clear();
  local_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    if (impulse[i].isZero(0)) continue;
    support_.push_back(static_cast<Index>(i));
    local_.push_back(into_start_frame ? Vec3<Real>((*turn)[i].transpose() * impulse[i]) : impulse[i]);
  }
  auto& x = object.system.state.position;
  auto& v = object.system.state.velocity;
  const Real inverse_dt = Real(1) / dt;
  for (std::size_t i = 0; i < n; ++i) {
    Vec3<Real> dx = Vec3<Real>::Zero();
    for (std::size_t k = 0; k < support_.size(); ++k) {
      dx += compliance_->template block<3, 3>(3 * static_cast<Index>(i), 3 * support_[k]) * local_[k];
    }
    if (turn) dx = ((*turn)[i] * dx).eval();
    if (order != ConstraintOrder::velocity) x[i] += dx;
    v[i] += dx * inverse_dt;
  }
}

template DenseMatrix<float> precompute_compliance(SimulatedObject<float>&, float);
template DenseMatrix<double> precompute_compliance(SimulatedObject<double>&, double);
template DenseMatrix<float> read_compliance_file(const std::filesystem::path&, std::size_t);
template DenseMatrix<double> read_compliance_file(const std::filesystem::path&, std::size_t);
template void write_compliance_file(const std::filesystem::path&, const DenseMatrix<float>&);
template void write_compliance_file(const std::filesystem::path&, const DenseMatrix<double>&);
template class PrecomputedConstraintCorrection<float>;
template class PrecomputedConstraintCorrection<double>;

}  // namespace fastcorot
