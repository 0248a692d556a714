// Turning PETSc's error codes into fastcorot::Error (errors come back as codes: petsc_runtime.cpp
// installs PETSc's silent handler), for the files that call PETSc.
#pragma once

#include <string>

namespace fastcorot {

// Throws fastcorot::Error "PETSc: WHAT: PETSc's message (PETSc error N)" when code is not 0.
void petsc_check(int code, const std::string& what);

}  // namespace fastcorot
