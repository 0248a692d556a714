// libFuzzer entry point of the vtk_legacy target (scripts/fuzz vtk_legacy); what it checks: fuzz_targets.h.
#include "fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fastcorot::fuzz::vtk_legacy({reinterpret_cast<const char*>(data), size});
  return 0;
}
