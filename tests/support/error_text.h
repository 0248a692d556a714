// The message of the fastcorot::Error a call throws, for tests that check what an error names.
#pragma once

#include "fastcorot/core/error.h"

#include <string>

namespace fastcorot::testing {

// The error's message, or "(no error)" when the call returns.
inline std::string error_of(auto&& call) {
  try {
    call();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace fastcorot::testing
