// The PETSc options of a command line (in every build: one without PETSc names them in its error).
#include "fastcorot/sim/petsc_runtime.h"

#include <cctype>

namespace fastcorot {

std::vector<std::string> take_petsc_options(std::vector<std::string>& arguments) {
  auto is_option = [](const std::string& a) {
    return a.size() > 2 && a[0] == '-' && std::isalpha(static_cast<unsigned char>(a[1]));
  };
  std::vector<std::string> petsc, rest;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    if (i == 0 || !is_option(arguments[i])) {
      rest.push_back(arguments[i]);
      continue;
    }
    petsc.push_back(arguments[i]);
    // As PETSc reads them: the next word is the value unless it is an option itself.
    if (i + 1 < arguments.size() && !is_option(arguments[i + 1]) && arguments[i + 1].rfind("--", 0) != 0) {
      petsc.push_back(arguments[++i]);
    }
  }
  arguments = std::move(rest);
  return petsc;
}

}  // namespace fastcorot
