#include "fastcorot/sim/petsc_runtime.h"

#include "fastcorot/core/error.h"
#include "petsc_check.h"

#include <petscsys.h>

#include <cstdlib>
#include <exception>
#include <limits>

namespace fastcorot {

namespace {

bool started_here = false;

std::string joined(const std::vector<std::string>& options) {
  std::string text;
  for (const auto& option : options) {
    if (!text.empty()) text += ' ';
    // PETSc splits the string at blanks: a value with blanks (a file name) keeps them in quotes.
    text += option.find(' ') == std::string::npos ? option : "\"" + option + "\"";
  }
  return text;
}

}  // namespace

void petsc_check(int code, const std::string& what) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(static_cast<PetscErrorCode>(code), &text, nullptr);
  throw make_error("PETSc: ", what, ": ", text ? text : "error", " (PETSc error ", code, ")");
}

bool petsc_available() { return true; }

bool petsc_initialised() {
  PetscBool initialised = PETSC_FALSE;
  PetscInitialized(&initialised);
  return initialised == PETSC_TRUE;
}

void initialise_petsc(const std::vector<std::string>& options) {
  if (!petsc_initialised()) {
    // PETSc's own handler prints a traceback and its signal handler catches crashes: errors here
    // come back as codes, turned into one line (petsc_check), and signals stay the program's.
    // Options given before initialisation count for it too (-log_view, -info).
    petsc_check(PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr), "options");
    if (!options.empty()) petsc_check(PetscOptionsInsertString(nullptr, joined(options).c_str()), "options");
    petsc_check(PetscInitializeNoArguments(), "initialisation");
    PetscPushErrorHandler(PetscIgnoreErrorHandler, nullptr);
    started_here = true;
    std::atexit(finalise_petsc);
    return;
  }
  if (!options.empty()) petsc_check(PetscOptionsInsertString(nullptr, joined(options).c_str()), "options");
}

void finalise_petsc() {
  if (!started_here || !petsc_initialised()) return;
  PetscBool finalised = PETSC_FALSE;
  PetscFinalized(&finalised);
  if (finalised == PETSC_TRUE) return;
  PetscFinalize();
}

int process_rank() {
  if (!petsc_initialised()) return 0;
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

int process_count() {
  if (!petsc_initialised()) return 1;
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

void on_every_rank(const std::function<void()>& section) {
  if (process_count() == 1) return section();
  std::exception_ptr failure;
  try {
    section();
  } catch (const Error&) {
    failure = std::current_exception();
  }
  const int rank = process_rank();
  int mine = failure ? rank : std::numeric_limits<int>::max(), first = 0;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  if (first == std::numeric_limits<int>::max()) return;
  if (first == rank) std::rethrow_exception(failure);
  throw ReportedElsewhere();
}

}  // namespace fastcorot
