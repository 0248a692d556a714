// A build without PETSc (-DFASTCOROT_WITH_PETSC=OFF): one process; PETSc options, the PETSc
// solver and distributed runs are clear errors.
#include "fastcorot/core/error.h"
#include "fastcorot/sim/distribution.h"
#include "fastcorot/sim/petsc_linear_solver.h"
#include "fastcorot/sim/petsc_runtime.h"

namespace fastcorot {

namespace {
constexpr const char* kWithout = "this fastcorot was built without PETSc (-DFASTCOROT_WITH_PETSC=OFF)";
}

bool petsc_available() { return false; }
bool petsc_initialised() { return false; }

void initialise_petsc(const std::vector<std::string>& options) {
  if (!options.empty()) throw make_error("PETSc option ", options.front(), ": ", kWithout);
}

void finalise_petsc() {}
int process_rank() { return 0; }
int process_count() { return 1; }
void on_every_rank(const std::function<void()>& section) { section(); }

struct PetscLinearSolver::Impl {};

PetscLinearSolver::PetscLinearSolver(Parameters parameters) : parameters_(std::move(parameters)) {
  throw make_error("PETScLinearSolver: ", kWithout);
}
PetscLinearSolver::~PetscLinearSolver() = default;
LinearSolveReport PetscLinearSolver::solve(const MechanicalSystem<double>&, const MatrixFactors<double>&,
                                           std::span<const Vec3<double>>, std::span<Vec3<double>>) {
  throw make_error("PETScLinearSolver: ", kWithout);
}
void PetscLinearSolver::distribute(std::shared_ptr<const Distribution>) {}
int PetscLinearSolver::pattern_builds() const { return 0; }
int PetscLinearSolver::preconditioner_builds() const { return 0; }
bool PetscLinearSolver::matrix_free() const { return false; }
std::vector<std::int64_t> PetscLinearSolver::carried_state() const { return {}; }
void PetscLinearSolver::restore_carried_state(const std::vector<std::int64_t>&) {}
std::size_t PetscLinearSolver::memory_bytes() const { return 0; }

struct Distribution::Ghosts {};
Distribution::Distribution(const MechanicalSystem<double>&, const TetMesh&) { throw make_error("distributed runs: ", kWithout); }
Distribution::~Distribution() = default;
void Distribution::sum_shared(std::span<Vec3<double>>) const {}
void Distribution::add_to_owners(std::span<Vec3<double>>) const {}
void Distribution::fill_ghosts(std::span<Vec3<double>>) const {}
double Distribution::sum(double value) const { return value; }
void Distribution::gather(std::span<const Vec3<double>>, std::span<Vec3<double>>) const {}

std::shared_ptr<Distribution> distribute(SimulatedObject<double>& object) {
  throw make_error(object.path, ": distributed runs: ", kWithout);
}

}  // namespace fastcorot
