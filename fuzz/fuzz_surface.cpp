// libFuzzer entry point of the surface target (scripts/fuzz surface); what it checks: fuzz_targets.h.
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fastcorot::fuzz::surface({reinterpret_cast<const char*>(data), size});
  return 0;
}
