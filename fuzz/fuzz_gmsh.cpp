// libFuzzer entry point of the gmsh target (scripts/fuzz gmsh); what it checks: fuzz_targets.h.
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fastcorot::fuzz::gmsh({reinterpret_cast<const char*>(data), size});
  return 0;
}
