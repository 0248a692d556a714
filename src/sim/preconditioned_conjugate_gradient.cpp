#include "fastcorot/sim/preconditioned_conjugate_gradient.h"

#include "fastcorot/core/error.h"
#include "fastcorot/core/parallel.h"
#include "fastcorot/fem/node_rotations.h"
#include "carried_bits.h"
#include "solver_vectors.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace fastcorot {

std::string_view preconditioner_name(Preconditioner preconditioner) {
  switch (preconditioner) {
    case Preconditioner::none: return "none";
    case Preconditioner::jacobi: return "jacobi";
    case Preconditioner::block_jacobi: return "block_jacobi";
    case Preconditioner::sparse_ldlt: return "sparse_ldlt";
    case Preconditioner::precomputed_warp: return "precomputed_warp";
    case Preconditioner::solver: return "solver";
  }
  return "?";
}

using carried_bits::from_bits;
using carried_bits::to_bits;

template <class Real>
PreconditionedConjugateGradientSolver<Real>::PreconditionedConjugateGradientSolver(Parameters parameters,
                                                                                   Index points)
    : parameters_(parameters) {
  if (parameters_.iterations < 1) {
    throw make_error("PCGLinearSolver: iterations = ", parameters_.iterations, ": must be at least 1");
  }
  if (!(parameters_.tolerance >= 0) || !std::isfinite(parameters_.tolerance)) {
    throw make_error("PCGLinearSolver: tolerance = ", parameters_.tolerance, ": must be finite and >= 0");
  }
  if (parameters_.update_step < 1) {
    throw make_error("PCGLinearSolver: update_step = ", parameters_.update_step, ": must be at least 1");
  }
  if (points < 0) throw make_error("PCGLinearSolver: ", points, " points");
  if (parameters_.preconditioner == Preconditioner::solver && !parameters_.solver) {
    throw make_error("PCGLinearSolver: a preconditioning solver is wanted, and none is given");
  }
  previous_.assign(static_cast<std::size_t>(points), Vec3<Real>::Zero());
  const bool factorised = parameters_.preconditioner == Preconditioner::sparse_ldlt ||
                          parameters_.preconditioner == Preconditioner::precomputed_warp ||
                          parameters_.preconditioner == Preconditioner::solver;
  if (!factorised) inverse_.assign(static_cast<std::size_t>(points), Mat3<Real>::Zero());
  if (parameters_.preconditioner == Preconditioner::precomputed_warp) {
    rotations_.assign(static_cast<std::size_t>(points), Mat3<Real>::Identity());
  }
}

template <class Real>
bool PreconditionedConjugateGradientSolver<Real>::carries_matrix() const {
  return parameters_.preconditioner == Preconditioner::precomputed_warp ||
         (parameters_.update_step > 1 && parameters_.preconditioner == Preconditioner::sparse_ldlt);
}

template <class Real>
bool PreconditionedConjugateGradientSolver<Real>::carries_rotations() const {
  return parameters_.preconditioner == Preconditioner::precomputed_warp && parameters_.update_step > 1;
}

template <class Real>
bool PreconditionedConjugateGradientSolver<Real>::carries_blocks() const {
  return parameters_.update_step > 1 && !inverse_.empty();
}

namespace {

template <class Real>
void factorise_or_throw(SparseFactorisation<Real>& factorisation, const Eigen::SparseMatrix<Real>& matrix) {
  if (!factorisation.factorise(matrix)) {
    throw make_error("PCGLinearSolver: sparse direct preconditioner: the system matrix could not be factorised "
                     "(singular: is every point held by a mass or an element?)");
  }
}

}  // namespace

template <class Real>
void PreconditionedConjugateGradientSolver<Real>::build_preconditioner(const MechanicalSystem<Real>& system,
                                                                       const MatrixFactors<Real>& factors) {
  if (parameters_.preconditioner == Preconditioner::solver) {
    parameters_.solver->build(system, factors);
    return;
  }
  if (parameters_.preconditioner == Preconditioner::precomputed_warp) {
    // A0 once, at the first solve (SOFA precomputes its inverse then); R every time.
    if (factorised_.nonZeros() == 0) {
      Eigen::SparseMatrix<Real> matrix = system.assemble(factors);
      matrix.makeCompressed();
      factorise_or_throw(factorisation_, matrix);
      factorised_ = std::move(matrix);
    }
    const auto field = std::find_if(system.force_fields.begin(), system.force_fields.end(),
                                    [](const auto& f) { return f->component() == "TetrahedronFEMForceField"; });
    if (parameters_.warp_rotations && field != system.force_fields.end()) {
      rotations_ = node_rotations(**field, system.size());
    } else {
      rotations_.assign(rotations_.size(), Mat3<Real>::Identity());
    }
    return;
  }
  if (parameters_.preconditioner == Preconditioner::sparse_ldlt) {
    Eigen::SparseMatrix<Real> matrix = system.assemble(factors);
    matrix.makeCompressed();
    factorise_or_throw(factorisation_, matrix);
    if (parameters_.update_step > 1) factorised_ = std::move(matrix);
    return;
  }
  system.diagonal_blocks(factors, inverse_);
  for (std::size_t i = 0; i < inverse_.size(); ++i) {
    Mat3<Real>& block = inverse_[i];
    if (block.isZero(0)) {
      // A point without mass and without elements (a mesh file's unused vertex): its row of the
      // matrix is zero, so is its residual; P leaves it alone, as CG would.
      block.setIdentity();
      continue;
    }
    if (parameters_.preconditioner == Preconditioner::jacobi) {
      const Vec3<Real> d = block.diagonal();
      for (int axis = 0; axis < 3; ++axis) {
        if (d[axis] == 0 || !std::isfinite(d[axis])) {
          throw make_error("PCGLinearSolver: Jacobi preconditioner: the system matrix's diagonal entry of point ",
                           i, ", axis ", "xyz"[axis], " is ", d[axis], " (cannot be inverted)");
        }
      }
      block = d.cwiseInverse().asDiagonal();
    } else {
      const Real determinant = block.determinant();
      if (determinant == 0 || !std::isfinite(determinant)) {
        throw make_error("PCGLinearSolver: block-Jacobi preconditioner: the system matrix's diagonal block of "
                         "point ", i, " has determinant ", determinant, " (cannot be inverted)");
      }
      block = block.inverse().eval();
    }
  }
}

template <class Real>
LinearSolveReport PreconditionedConjugateGradientSolver<Real>::solve(const MechanicalSystem<Real>& system,
                                                                     const MatrixFactors<Real>& factors,
                                                                     std::span<const Vec3<Real>> rhs,
                                                                     std::span<Vec3<Real>> x) {
  using solver_vectors::dot_range;
  using solver_vectors::flat;
  const std::size_t n = previous_.size();
  if (rhs.size() != n || x.size() != n || static_cast<std::size_t>(system.size()) != n) {
    throw make_error("PCGLinearSolver: a system of ", system.size(), " points; this solver was made for ", n);
  }
  const int threads = system.threads();
  double* vector_time = system.timer_slot(&PhaseTimes::solver_vectors);
  if (parameters_.preconditioner != Preconditioner::none && !reuse_preconditioner_ && solves_ % parameters_.update_step == 0) {
    const PhaseTimer timer(vector_time);
    build_preconditioner(system, factors);
  }
  ++solves_;
  r_.resize(n);
  w_.resize(n);
  q_.resize(n);
  s_.resize(n);
  std::copy(previous_.begin(), previous_.end(), x.begin());
  const bool warp = parameters_.preconditioner == Preconditioner::precomputed_warp;
  if (warp) t_.resize(n);
  system.multiply(factors, x, q_);  // A x0, even for x0 = 0, as SOFA does

  // The vectors as flat arrays of coordinates; passes that apply P run over chunks of points.
  const Real* b = flat<Real>(rhs);
  Real* r = flat<Real>(std::span<Vec3<Real>>(r_));
  Real* w = flat<Real>(std::span<Vec3<Real>>(w_));
  Real* s = flat<Real>(std::span<Vec3<Real>>(s_));
  const Real* q = flat<Real>(std::span<const Vec3<Real>>(q_));
  Real* xs = flat<Real>(x);
  const Real* inverse = inverse_.empty() ? nullptr : inverse_.data()->data();  // nine values per point, column-major
  const Preconditioner kind = parameters_.preconditioner;
  const bool by_solver = kind == Preconditioner::solver;
  const bool direct = kind == Preconditioner::sparse_ldlt || warp || by_solver;
  // z = P r for the points [begin, end) (already done for the direct preconditioner), returning
  // sum r . z over them: one partial sum per axis (three chains of additions instead of one), in
  // point order, then x + y + z.
  const auto precondition_points = [&](Real* z, std::size_t begin, std::size_t end) {
    Real sum_x = 0, sum_y = 0, sum_z = 0;
    for (std::size_t i = begin; i < end; ++i) {
      const Real* m = inverse + 9 * i;
      const Real r0 = r[3 * i], r1 = r[3 * i + 1], r2 = r[3 * i + 2];
      Real z0 = r0, z1 = r1, z2 = r2;
      if (direct) {
        z0 = z[3 * i];
        z1 = z[3 * i + 1];
        z2 = z[3 * i + 2];
      } else if (kind == Preconditioner::jacobi) {
        z0 = m[0] * r0;
        z1 = m[4] * r1;
        z2 = m[8] * r2;
      } else if (kind == Preconditioner::block_jacobi) {
        z0 = m[0] * r0 + m[3] * r1 + m[6] * r2;
        z1 = m[1] * r0 + m[4] * r1 + m[7] * r2;
        z2 = m[2] * r0 + m[5] * r1 + m[8] * r2;
      }
      z[3 * i] = z0;
      z[3 * i + 1] = z1;
      z[3 * i + 2] = z2;
      sum_x += r0 * z0;
      sum_y += r1 * z1;
      sum_z += r2 * z2;
    }
    return (sum_x + sum_y) + sum_z;
  };
  // Runs `pass` (which sets r) over the points, then z = P r, returning r . z: one pass per chunk of
  // points for the point-wise preconditioners; the direct one solves for the whole vector between
  // the pass and the sum.
  const auto update_and_precondition = [&](const auto& pass, Real* z) {
    if (warp) {
      // z = R A0^-1 R^T r
      parallel_ranges(threads, n, [&](std::size_t begin, std::size_t end) {
        pass(begin, end);
        for (std::size_t i = begin; i < end; ++i) t_[i] = rotations_[i].transpose() * r_[i];
      });
      Real* t = flat<Real>(std::span<Vec3<Real>>(t_));
      factorisation_.solve(t, z, static_cast<Index>(3 * n));
      Vec3<Real>* zv = reinterpret_cast<Vec3<Real>*>(z);
      parallel_ranges(threads, n, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) zv[i] = (rotations_[i] * zv[i]).eval();
      });
    } else if (direct) {
      parallel_ranges(threads, n, pass);
      if (by_solver) {
        parameters_.solver->apply(r, z, static_cast<Index>(3 * n));
      } else {
        factorisation_.solve(r, z, static_cast<Index>(3 * n));
      }
    }
    return parallel_sum<Real>(threads, n, [&](std::size_t begin, std::size_t end) {
      if (!direct) pass(begin, end);
      return precondition_points(z, begin, end);
    });
  };
  Real b_norm = 0, rho = 0;
  {
    const PhaseTimer timer(vector_time);
    b_norm = parallel_sum<Real>(threads, 3 * n, [&](std::size_t begin, std::size_t end) {
      return dot_range(b, b, begin, end);
    });
    rho = update_and_precondition(
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = 3 * begin; i < 3 * end; ++i) r[i] = b[i] - q[i];
        },
        w);
  }
  const Real tolerance = parameters_.tolerance * b_norm;
  LinearSolveReport report;
  for (int iteration = 1; iteration <= parameters_.iterations && rho > tolerance; ++iteration) {
    system.multiply(factors, w_, q_);
    const PhaseTimer timer(vector_time);
    const Real den = parallel_sum<Real>(threads, 3 * n, [&](std::size_t begin, std::size_t end) {
      return dot_range(w, q, begin, end);
    });
    // SOFA divides regardless; a zero or non-finite curvature would only spread NaN, so stop here.
    if (den == 0 || !std::isfinite(den)) break;
    const Real alpha = rho / den;
    const Real rho_previous = rho;
    rho = update_and_precondition(
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = 3 * begin; i < 3 * end; ++i) {
            xs[i] += alpha * w[i];
            r[i] -= alpha * q[i];
          }
        },
        s);
    const Real beta = rho / rho_previous;
    parallel_ranges(threads, 3 * n, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) w[i] = s[i] + beta * w[i];
    });
    report.iterations = iteration;
  }
  std::copy(x.begin(), x.end(), previous_.begin());
  report.relative_residual = b_norm > 0 ? std::sqrt(std::max(rho, Real(0)) / b_norm) : Real(0);
  return report;
}

template <class Real>
LinearSolveReport PreconditionedConjugateGradientSolver<Real>::solve_again(const MechanicalSystem<Real>& system, const MatrixFactors<Real>& factors,
                                        std::span<const Vec3<Real>> rhs, std::span<Vec3<Real>> x) {
  const std::int64_t solves = solves_;
  const std::vector<Vec3<Real>> previous = previous_;
  std::fill(previous_.begin(), previous_.end(), Vec3<Real>::Zero());
  reuse_preconditioner_ = true;
  LinearSolveReport report;
  try {
    report = solve(system, factors, rhs, x);
  } catch (...) {
    reuse_preconditioner_ = false;
    solves_ = solves;
    previous_ = previous;
    throw;
  }
  reuse_preconditioner_ = false;
  solves_ = solves;
  previous_ = previous;
  return report;
}

template <class Real>
std::vector<std::int64_t> PreconditionedConjugateGradientSolver<Real>::carried_state() const {
  // Solve count, previous solution, then the blocks or the rotations, then the matrix.
  std::vector<std::int64_t> state{solves_};
  for (const auto& v : previous_) {
    for (int c = 0; c < 3; ++c) state.push_back(to_bits(v[c]));
  }
  const auto push_blocks = [&state](const std::vector<Mat3<Real>>& blocks) {
    for (const auto& block : blocks) {
      for (int c = 0; c < 9; ++c) state.push_back(to_bits(block.data()[c]));
    }
  };
  if (carries_blocks()) push_blocks(inverse_);
  if (carries_rotations()) push_blocks(rotations_);
  if (carries_matrix()) {
    // The factorised matrix (compressed columns: nonzero count, column starts, row indices, values);
    // none before the first solve.
    const Eigen::SparseMatrix<Real>& m = factorised_;
    state.push_back(m.nonZeros());
    if (m.nonZeros() > 0) {
      state.insert(state.end(), m.outerIndexPtr(), m.outerIndexPtr() + m.outerSize() + 1);
      state.insert(state.end(), m.innerIndexPtr(), m.innerIndexPtr() + m.nonZeros());
      for (Eigen::Index k = 0; k < m.nonZeros(); ++k) state.push_back(to_bits(m.valuePtr()[k]));
    }
  }
  if (parameters_.solver && parameters_.preconditioner == Preconditioner::solver) {
    const auto own = parameters_.solver->carried_state();
    state.insert(state.end(), own.begin(), own.end());
  }
  return state;
}

template <class Real>
void PreconditionedConjugateGradientSolver<Real>::check_carried_state(const std::vector<std::int64_t>& state) const {
  const std::size_t n = previous_.size();
  const bool blocks = carries_blocks() || carries_rotations();
  const bool matrix = carries_matrix();
  const std::size_t expected = 1 + 3 * n + (blocks ? 9 * n : 0);
  const bool by_solver = parameters_.preconditioner == Preconditioner::solver;
  if (by_solver) {
    if (state.size() <= expected || state[0] < 0) {
      throw make_error("PCGLinearSolver: expected more than ", expected, " values to restore (solve count, ", n,
                       " points' previous solution, ", parameters_.solver->component(), "'s state), got ", state.size());
    }
    parameters_.solver->check_carried_state(std::span<const std::int64_t>(state).subspan(expected));
    return;
  }
  if ((matrix ? state.size() <= expected : state.size() != expected) || state[0] < 0) {
    throw make_error("PCGLinearSolver: expected ", matrix ? "more than " : "", expected,
                     " values to restore (solve count, ", n, " points' previous solution",
                     carries_blocks() ? ", preconditioner blocks" : "", carries_rotations() ? ", rotations" : "",
                     matrix ? ", factorised matrix" : "", "), got ", state.size());
  }
  if (matrix) carried_matrix(std::span<const std::int64_t>(state).subspan(expected));
}

template <class Real>
void PreconditionedConjugateGradientSolver<Real>::restore_carried_state(const std::vector<std::int64_t>& state) {
  check_carried_state(state);
  std::size_t k = 1;
  for (auto& v : previous_) {
    for (int c = 0; c < 3; ++c) v[c] = from_bits<Real>(state[k++]);
  }
  const auto read_blocks = [&](std::vector<Mat3<Real>>& blocks) {
    for (auto& block : blocks) {
      for (int c = 0; c < 9; ++c) block.data()[c] = from_bits<Real>(state[k++]);
    }
  };
  if (carries_blocks()) read_blocks(inverse_);
  if (carries_rotations()) read_blocks(rotations_);
  if (parameters_.preconditioner == Preconditioner::solver) {
    parameters_.solver->restore_carried_state(std::span<const std::int64_t>(state).subspan(k));
  }
  if (carries_matrix()) {
    factorised_ = carried_matrix(std::span<const std::int64_t>(state).subspan(k));
    if (factorised_.nonZeros() > 0) factorise_or_throw(factorisation_, factorised_);
  }
  solves_ = state[0];
}

template <class Real>
Eigen::SparseMatrix<Real> PreconditionedConjugateGradientSolver<Real>::carried_matrix(
    std::span<const std::int64_t> state) const {
  const auto size = static_cast<std::int64_t>(3 * previous_.size());
  const std::int64_t nonzeros = state[0];
  const auto fail = [&](const char* why) {
    return make_error("PCGLinearSolver: the carried factorised matrix is inconsistent (", why, ")");
  };
  if (nonzeros < 0 || nonzeros > size * size) throw fail("nonzero count");
  if (nonzeros == 0) {
    if (state.size() != 1) throw fail("values after an empty matrix");
    return {};
  }
  if (static_cast<std::int64_t>(state.size()) != 1 + (size + 1) + 2 * nonzeros) throw fail("length");
  const auto outer = state.subspan(1, static_cast<std::size_t>(size + 1));
  const auto inner = state.subspan(static_cast<std::size_t>(size + 2), static_cast<std::size_t>(nonzeros));
  const auto values = state.subspan(static_cast<std::size_t>(size + 2 + nonzeros));
  if (outer.front() != 0 || outer.back() != nonzeros) throw fail("column starts");
  std::vector<Eigen::Triplet<Real>> entries;
  entries.reserve(static_cast<std::size_t>(nonzeros));
  for (std::int64_t column = 0; column < size; ++column) {
    const std::int64_t begin = outer[static_cast<std::size_t>(column)];
    const std::int64_t end = outer[static_cast<std::size_t>(column + 1)];
    if (begin > end || end > nonzeros) throw fail("column starts");
    for (std::int64_t k = begin; k < end; ++k) {
      const std::int64_t row = inner[static_cast<std::size_t>(k)];
      if (row < 0 || row >= size || (k > begin && row <= inner[static_cast<std::size_t>(k - 1)])) {
        throw fail("row indices");
      }
      entries.emplace_back(static_cast<Index>(row), static_cast<Index>(column),
                           from_bits<Real>(values[static_cast<std::size_t>(k)]));
    }
  }
  Eigen::SparseMatrix<Real> m(static_cast<Index>(size), static_cast<Index>(size));
  m.setFromTriplets(entries.begin(), entries.end());
  m.makeCompressed();
  return m;
}

template class PreconditionedConjugateGradientSolver<float>;
template class PreconditionedConjugateGradientSolver<double>;

}  // namespace fastcorot
