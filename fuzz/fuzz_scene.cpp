// libFuzzer entry point of the scene target (scripts/fuzz scene); what it checks: fuzz_targets.h.
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fastcorot::fuzz::scene({reinterpret_cast<const char*>(data), size}, FASTCOROT_EXAMPLES_DIR);
  return 0;
}
