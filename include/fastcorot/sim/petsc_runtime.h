// PETSc and MPI for the whole process. fastcorot's large and distributed solves run on PETSc
// (Krylov solvers, algebraic multigrid, MPI matrices and vectors; docs/scaling.md). PETSc is
// initialised once per process, by the command line with the PETSc options it was given
// (`-ksp_type cg -pc_type gamg -ksp_monitor`, as PETSc programs take them), or on first use by a
// PETScLinearSolver (Python, tests); it is finalised at exit. Without PETSc in the build
// (-DFASTCOROT_WITH_PETSC=OFF) the process is one rank and asking for PETSc is a clear error.
#pragma once

#include "fastcorot/core/error.h"

#include <functional>
#include <string>
#include <vector>

namespace fastcorot {

// Whether this build has PETSc (and MPI).
bool petsc_available();

// Initialises PETSc (and MPI, when mpirun has not) once for the process, with `options` added to
// PETSc's options database ("-name value" items, as on a PETSc command line). Later calls add their
// options. Throws fastcorot::Error without PETSc in the build when options are given, or when
// PETSc rejects them.
void initialise_petsc(const std::vector<std::string>& options = {});
bool petsc_initialised();
// Finalises PETSc (and MPI, if PETSc started it); nothing when PETSc was never initialised.
void finalise_petsc();

// This process's rank and the number of ranks (MPI_COMM_WORLD); 0 and 1 when PETSc is not
// initialised or not in the build.
int process_rank();
int process_count();

// Splits the PETSc options out of a command line: every argument that begins with one '-' and a
// letter and is longer than two characters (`-ksp_type`, `-log_view`; not `--steps`, not `-o`) is a
// PETSc option, with the next argument as its value unless that one is itself an option. Returns the
// PETSc options and leaves the rest (program name first) in `arguments`.
std::vector<std::string> take_petsc_options(std::vector<std::string>& arguments);

// The error of a rank whose work stopped because another rank failed, which reported it: front
// ends exit with status 2 without printing it, so that a failure is one line, not one per rank.
class ReportedElsewhere : public Error {
 public:
  ReportedElsewhere() : Error("stopped: another rank reported an error") {}
};

// Runs `section` on every rank (collective after it). When it throws fastcorot::Error on some
// rank, the lowest such rank rethrows its error and the others throw ReportedElsewhere, so that
// every rank stops together and none waits for the others in vain. `section` must not end in a
// collective call that a failing rank would skip. With one rank: just `section()`.
void on_every_rank(const std::function<void()>& section);

}  // namespace fastcorot
