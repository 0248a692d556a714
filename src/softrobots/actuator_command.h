// The command data SoftRobots' actuators share (internal to src/softrobots): `value`, the commands,
// and `valueIndex`, the one imposed; checked, and written by scripts between steps.
#pragma once

#include "fastcorot/core/error.h"

#include <cmath>
#include <span>
#include <string>
#include <vector>

namespace fastcorot::softrobots_detail {

// Throws fastcorot::Error for an empty `value`, an index beyond it or a command that is not finite.
template <class Real>
void check_command(const std::vector<Real>& value, std::size_t index) {
  if (value.empty()) throw make_error("value is empty: one command at least is needed");
  if (index >= value.size()) throw make_error("valueIndex = ", index, " but value has ", value.size(), " entries");
  for (std::size_t k = 0; k < value.size(); ++k) {
    if (!std::isfinite(value[k])) throw make_error("value[", k, "] is not finite");
  }
}

// A script's write of `value` or `valueIndex` (checked by the caller after); false for another name.
template <class Real>
bool write_command(const std::string& name, std::span<const double> values, std::vector<Real>& value, std::size_t& index) {
  if (name == "value") {
    value.assign(values.begin(), values.end());
    return true;
  }
  if (name != "valueIndex") return false;
  if (values.size() != 1 || values[0] < 0 || values[0] != std::floor(values[0])) {
    throw make_error("valueIndex: expected one whole number >= 0");
  }
  index = static_cast<std::size_t>(values[0]);
  return true;
}

// Runs `write` on `parameters` and `check` after it; when either throws, puts the parameters back
// and rethrows naming `where`.
template <class Parameters, class Write, class Check>
void write_checked(const std::string& where, Parameters& parameters, const Write& write, const Check& check) {
  const Parameters kept = parameters;
  try {
    write();
    check();
  } catch (const Error& error) {
    parameters = kept;
    throw make_error(where, ": ", error.what());
  }
}

}  // namespace fastcorot::softrobots_detail
