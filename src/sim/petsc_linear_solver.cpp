#include "fastcorot/sim/petsc_linear_solver.h"

#include "fastcorot/core/error.h"
#include "fastcorot/sim/distribution.h"
#include "fastcorot/sim/petsc_runtime.h"
#include "petsc_check.h"
#include "petsc_matrix.h"

#include <petscksp.h>

#include <algorithm>
#include <cmath>
#include <exception>

namespace fastcorot {

namespace {

// The value of a PETSc option of the options database ("" when not given).
std::string option_value(const char* name) {
  char value[256] = "";
  PetscBool set = PETSC_FALSE;
  PetscOptionsGetString(nullptr, nullptr, name, value, sizeof value, &set);
  return set ? std::string(value) : std::string();
}

bool option_given(const char* name) {
  PetscBool set = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, name, &set);
  return set == PETSC_TRUE;
}

// Sets the solver and preconditioner types and tolerances, then PETSc's options over them.
void configure(KSP ksp, const PetscLinearSolver::Parameters& parameters) {
  if (KSPSetType(ksp, parameters.ksp.c_str()) != 0) {
    throw make_error("unknown ksp \"", parameters.ksp, "\" (PETSc's KSP types: cg, gmres, minres, ...)");
  }
  PC pc = nullptr;
  petsc_check(KSPGetPC(ksp, &pc), "preconditioner");
  if (PCSetType(pc, parameters.pc.c_str()) != 0) {
    throw make_error("unknown pc \"", parameters.pc, "\" (PETSc's PC types: gamg, jacobi, bjacobi, ilu, ...)");
  }
  // GAMG's aggregates and interpolation depend on the pattern and the rest shape, not on the
  // rotations: they are built once per pattern and reused; the coarse operators are recomputed.
  PCGAMGSetReuseInterpolation(pc, PETSC_TRUE);
  petsc_check(KSPSetTolerances(ksp, parameters.tolerance, PETSC_DEFAULT, PETSC_DEFAULT, parameters.max_iterations),
              "tolerances");
  // The command line's types are tried first: KSPSetFromOptions would fail on an unknown one
  // halfway through its options (and leak what it had read).
  const auto unknown = [](const char* name, const std::string& value) {
    return make_error("PETSc option ", name, " ", value, ": unknown type (or a package this PETSc lacks)");
  };
  if (const std::string type = option_value("-ksp_type"); !type.empty() && KSPSetType(ksp, type.c_str()) != 0) {
    throw unknown("-ksp_type", type);
  }
  if (const std::string type = option_value("-pc_type"); !type.empty() && PCSetType(pc, type.c_str()) != 0) {
    throw unknown("-pc_type", type);
  }
  petsc_check(KSPSetFromOptions(ksp), "the -ksp_* and -pc_* options");
  KSPType type = nullptr;
  KSPGetType(ksp, &type);
  // The tolerance is on the true residual, as for the other solvers here (CG's default norm
  // would be the preconditioned one).
  if (!option_given("-ksp_norm_type") && type && std::string(type) == KSPCG) {
    petsc_check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "norm type");
  }
}

bool is_preonly(KSP ksp) {
  KSPType type = nullptr;
  KSPGetType(ksp, &type);
  return type && std::string(type) == KSPPREONLY;
}

}  // namespace

struct PetscLinearSolver::Impl {
  std::shared_ptr<const Distribution> distribution;
  std::unique_ptr<PetscMatrix> matrix;
  Mat product = nullptr;  // the matrix-free operator (a shell around MechanicalSystem::multiply)
  KSP ksp = nullptr;
  Vec rhs = nullptr, solution = nullptr;
  // What the pattern was built for: point count, held points, tetrahedra of each force field.
  std::vector<Index> pattern_key;
  int builds = 0;
  int preconditioner_builds = 0;
  // The rebuild cadence (carried by checkpoints): solves since the preconditioner was last
  // rebuilt, the iterations of the first solve after it, and whether a solve has since needed
  // rebuild_growth times as many.
  long solves_since_setup = 0;
  long reference_iterations = 0;
  bool rebuild_due = false;
  bool set_up = false;  // the preconditioner was built since the pattern was
  // The system and factors of the solve under way, for the shell's products, and the error one
  // of them threw (PETSc's callbacks return codes: it is rethrown after the solve).
  const MechanicalSystem<double>* system = nullptr;
  const MatrixFactors<double>* factors = nullptr;
  std::exception_ptr product_failure;
  std::vector<Vec3<double>> product_in, product_out;  // distributed runs: whole-object vectors

  ~Impl() { release(); }
  void release() {
    if (ksp) KSPDestroy(&ksp);
    if (product) MatDestroy(&product);
    if (rhs) VecDestroy(&rhs);
    if (solution) VecDestroy(&solution);
    matrix.reset();
    set_up = false;
  }
  bool distributed() const { return distribution && distribution->ranks() > 1; }

  static std::vector<Index> key_of(const MechanicalSystem<double>& system) {
    std::vector<Index> key{system.size(), static_cast<Index>(system.fixed.size()),
                           static_cast<Index>(system.isolated.size()), static_cast<Index>(system.moving.size())};
    key.insert(key.end(), system.fixed.begin(), system.fixed.end());
    key.insert(key.end(), system.isolated.begin(), system.isolated.end());
    key.insert(key.end(), system.moving.begin(), system.moving.end());
    for (const auto& field : system.force_fields) key.push_back(field->mesh().num_tetrahedra());
    return key;
  }

  // A new matrix and solver for `system`'s pattern (general: through assemble(), with values).
  void build(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors, const Parameters& parameters,
             bool general) {
    release();
    // A new pattern (after a topological change) starts the cadence again; the first one keeps
    // the cadence a checkpoint restored.
    if (builds++ > 0) {
      solves_since_setup = reference_iterations = 0;
      rebuild_due = false;
    }
    matrix = std::make_unique<PetscMatrix>(distribution);
    if (general) matrix->build_general(system, factors, parameters.near_null_space);
    else matrix->build(system, parameters.near_null_space);
    petsc_check(MatCreateVecs(matrix->mat(), &solution, &rhs), "vectors");
    petsc_check(KSPCreate(matrix->comm(), &ksp), "solver");
    configure(ksp, parameters);
    if (parameters.matrix_free && !general && !is_preonly(ksp)) {
      PetscInt rows = 0, columns = 0, global_rows = 0, global_columns = 0;
      MatGetLocalSize(matrix->mat(), &rows, &columns);
      MatGetSize(matrix->mat(), &global_rows, &global_columns);
      petsc_check(MatCreateShell(matrix->comm(), rows, columns, global_rows, global_columns, this, &product),
                  "matrix-free operator");
      petsc_check(MatShellSetOperation(product, MATOP_MULT, reinterpret_cast<void (*)(void)>(&multiply_callback)),
                  "matrix-free operator");
      if (distributed()) {
        product_in.assign(static_cast<std::size_t>(system.size()), Vec3<double>::Zero());
        product_out.assign(static_cast<std::size_t>(system.size()), Vec3<double>::Zero());
      }
    }
  }

  static PetscErrorCode multiply_callback(Mat shell, Vec in, Vec out) {
    Impl* impl = nullptr;
    MatShellGetContext(shell, &impl);
    try {
      impl->multiply(in, out);
    } catch (...) {
      impl->product_failure = std::current_exception();
      return PETSC_ERR_LIB;
    }
    return 0;
  }

  // out = A in through the system's matrix-free product, with the identity at held points (as the
  // assembled matrix has it).
  void multiply(Vec in, Vec out) {
    const PetscScalar* x = nullptr;
    PetscScalar* y = nullptr;
    petsc_check(VecGetArrayRead(in, &x), "product");
    petsc_check(VecGetArray(out, &y), "product");
    const PetscInt owned = matrix->owned();
    if (!distributed()) {
      // The vectors' three values per point in point order are the system's own layout.
      const std::span<const Vec3<double>> dx(reinterpret_cast<const Vec3<double>*>(x), static_cast<std::size_t>(owned));
      const std::span<Vec3<double>> df(reinterpret_cast<Vec3<double>*>(y), static_cast<std::size_t>(owned));
      system->multiply(*factors, dx, df);
      for (const auto* points : {&system->fixed, &system->isolated, &system->moving}) {
        for (Index i : *points) df[static_cast<std::size_t>(i)] = dx[static_cast<std::size_t>(i)];
      }
    } else {
      // Owned values in, ghost copies from their owners; this rank's part of the product, whose
      // values at shared points go to their owners (only owned rows go back to PETSc).
      for (PetscInt k = 0; k < owned; ++k) {
        product_in[static_cast<std::size_t>(matrix->owned_point(k))] = {x[3 * k], x[3 * k + 1], x[3 * k + 2]};
      }
      distribution->fill_ghosts(product_in);
      system->multiply_own_part(*factors, product_in, product_out);
      distribution->add_to_owners(product_out);
      const std::vector<bool>& held = matrix->held();
      for (PetscInt k = 0; k < owned; ++k) {
        const auto p = static_cast<std::size_t>(matrix->owned_point(k));
        const Vec3<double>& value = held[p] ? product_in[p] : product_out[p];
        for (int d = 0; d < 3; ++d) y[3 * k + d] = value[d];
      }
    }
    VecRestoreArray(out, &y);
    VecRestoreArrayRead(in, &x);
  }
};

PetscLinearSolver::PetscLinearSolver(Parameters parameters) : parameters_(std::move(parameters)), impl_(std::make_unique<Impl>()) {
  if (!(parameters_.tolerance > 0) || !std::isfinite(parameters_.tolerance)) {
    throw make_error("tolerance ", parameters_.tolerance, ": must be > 0");
  }
  if (parameters_.max_iterations < 1) throw make_error("maxIterations ", parameters_.max_iterations, ": must be >= 1");
  if (parameters_.rebuild_every < 0) throw make_error("rebuildEvery ", parameters_.rebuild_every, ": must be >= 0 (0: never)");
  if (!(parameters_.rebuild_growth == 0 || parameters_.rebuild_growth >= 1) || !std::isfinite(parameters_.rebuild_growth)) {
    throw make_error("rebuildGrowth ", parameters_.rebuild_growth, ": must be >= 1 (0: never)");
  }
  initialise_petsc();
  // The types and the command line's options are checked now, when the scene is built.
  KSP probe = nullptr;
  petsc_check(KSPCreate(PETSC_COMM_SELF, &probe), "solver");
  try {
    configure(probe, parameters_);
  } catch (const Error&) {
    KSPDestroy(&probe);
    throw;
  }
  KSPDestroy(&probe);
}

PetscLinearSolver::~PetscLinearSolver() = default;

void PetscLinearSolver::distribute(std::shared_ptr<const Distribution> distribution) {
  impl_->release();
  impl_->pattern_key.clear();
  impl_->distribution = std::move(distribution);
}

int PetscLinearSolver::pattern_builds() const { return impl_->builds; }

int PetscLinearSolver::preconditioner_builds() const { return impl_->preconditioner_builds; }

bool PetscLinearSolver::matrix_free() const { return impl_->product != nullptr; }

std::vector<std::int64_t> PetscLinearSolver::carried_state() const {
  return {impl_->solves_since_setup, impl_->reference_iterations, impl_->rebuild_due ? 1 : 0};
}

void PetscLinearSolver::restore_carried_state(const std::vector<std::int64_t>& state) {
  check_carried_state(state);
  if (state[0] < 0 || state[1] < 0 || (state[2] != 0 && state[2] != 1)) {
    throw make_error("PETScLinearSolver: a bad rebuild cadence (", state[0], " solves, ", state[1], " iterations, ",
                     state[2], ")");
  }
  impl_->solves_since_setup = static_cast<long>(state[0]);
  impl_->reference_iterations = static_cast<long>(state[1]);
  impl_->rebuild_due = state[2] == 1;
}

std::size_t PetscLinearSolver::memory_bytes() const { return impl_->matrix ? impl_->matrix->memory_bytes() : 0; }

LinearSolveReport PetscLinearSolver::solve(const MechanicalSystem<double>& system, const MatrixFactors<double>& factors,
                                           std::span<const Vec3<double>> rhs, std::span<Vec3<double>> x) {
  Impl& impl = *impl_;
  const bool general = !system.projections.empty() || !system.couplings.empty();
  if (general && impl.distributed()) {
    throw make_error("PETScLinearSolver: partial projective constraints and attachments are not supported in a "
                     "distributed run (run on one process)");
  }
  {
    const PhaseTimer timer(system.timer_slot(&PhaseTimes::solver_vectors));  // assembly and set-up
    if (general) {
      // The general assembly's pattern follows the projections: a new matrix every solve.
      impl.build(system, factors, parameters_, true);
      impl.pattern_key.clear();
    } else if (std::vector<Index> key = Impl::key_of(system); !impl.matrix || key != impl.pattern_key) {
      impl.build(system, factors, parameters_, false);
      impl.pattern_key = std::move(key);
    }
    // The preconditioner is built from the current matrix when it has not been for this pattern,
    // after rebuild_every solves, after a solve that needed rebuild_growth times the iterations
    // of the first one with it, and every solve when the solver is the preconditioner alone (as
    // with preonly). Matrix-free, the matrix is assembled only then.
    // (A first build for a pattern leaves the cadence alone: a resumed run keeps the one its
    // checkpoint carried, so its later rebuilds fall where the uninterrupted run's did.)
    const bool every_solve = !impl.product && is_preonly(impl.ksp);
    const bool scheduled = every_solve || impl.rebuild_due ||
                           (parameters_.rebuild_every > 0 && impl.solves_since_setup >= parameters_.rebuild_every);
    const bool rebuild = scheduled || !impl.set_up;
    if (!general && (rebuild || !impl.product)) impl.matrix->fill(system, factors);
    PetscScalar* b = nullptr;
    petsc_check(VecGetArray(impl.rhs, &b), "right-hand side");
    for (PetscInt k = 0; k < impl.matrix->owned(); ++k) {
      const Vec3<double>& value = rhs[static_cast<std::size_t>(impl.matrix->owned_point(k))];
      for (int d = 0; d < 3; ++d) b[3 * k + d] = value[d];
    }
    petsc_check(VecRestoreArray(impl.rhs, &b), "right-hand side");
    Mat a = impl.product ? impl.product : impl.matrix->mat();
    petsc_check(KSPSetOperators(impl.ksp, a, impl.matrix->mat()), "solver operators");
    petsc_check(KSPSetReusePreconditioner(impl.ksp, rebuild ? PETSC_FALSE : PETSC_TRUE), "preconditioner reuse");
    impl.solves_since_setup = scheduled ? 1 : impl.solves_since_setup + 1;
    impl.preconditioner_builds += rebuild ? 1 : 0;
    impl.rebuild_due = false;
    impl.set_up = true;
  }
  const bool first_with_preconditioner = impl.solves_since_setup == 1;
  impl.system = &system;
  impl.factors = &factors;
  impl.product_failure = nullptr;
  const int code = KSPSolve(impl.ksp, impl.rhs, impl.solution);
  impl.system = nullptr;
  impl.factors = nullptr;
  if (impl.product_failure) std::rethrow_exception(impl.product_failure);
  if (code != 0) petsc_check(code, "solve (ksp " + parameters_.ksp + ", pc " + parameters_.pc + ")");
  KSPConvergedReason reason;
  KSPGetConvergedReason(impl.ksp, &reason);
  PetscInt iterations = 0;
  KSPGetIterationNumber(impl.ksp, &iterations);
  PetscReal residual = 0, rhs_norm = 0;
  KSPGetResidualNorm(impl.ksp, &residual);
  VecNorm(impl.rhs, NORM_2, &rhs_norm);
  const double relative = rhs_norm > 0 ? residual / rhs_norm : 0.0;
  if (reason < 0) {
    KSPType type = nullptr;
    PC pc = nullptr;
    PCType pc_type = nullptr;
    KSPGetType(impl.ksp, &type);
    KSPGetPC(impl.ksp, &pc);
    PCGetType(pc, &pc_type);
    throw make_error("PETScLinearSolver (ksp ", type ? type : "?", ", pc ", pc_type ? pc_type : "?", "): the solve did not converge: ",
                     KSPConvergedReasons[reason], " after ", iterations, " iterations (relative residual ", relative,
                     ", tolerance ", parameters_.tolerance, "); raise maxIterations (-ksp_max_it) or check the scene");
  }
  if (first_with_preconditioner) {
    impl.reference_iterations = iterations;
  } else if (parameters_.rebuild_growth > 0 && iterations > parameters_.rebuild_growth * impl.reference_iterations &&
             iterations > impl.reference_iterations + 2) {
    impl.rebuild_due = true;
  }
  const PetscScalar* solution = nullptr;
  petsc_check(VecGetArrayRead(impl.solution, &solution), "solution");
  std::fill(x.begin(), x.end(), Vec3<double>::Zero());
  for (PetscInt k = 0; k < impl.matrix->owned(); ++k) {
    x[static_cast<std::size_t>(impl.matrix->owned_point(k))] = {solution[3 * k], solution[3 * k + 1], solution[3 * k + 2]};
  }
  VecRestoreArrayRead(impl.solution, &solution);
  // Ghost copies get their owners' values.
  if (impl.distributed()) impl.distribution->fill_ghosts(x);
  return {static_cast<int>(iterations), relative};
}

}  // namespace fastcorot
