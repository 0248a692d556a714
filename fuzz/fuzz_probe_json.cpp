// libFuzzer entry point of the probe_json target (scripts/fuzz probe_json); what it checks: fuzz_targets.h.
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fastcorot::fuzz::probe_json({reinterpret_cast<const char*>(data), size});
  return 0;
}
