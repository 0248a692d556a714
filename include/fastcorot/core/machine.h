// What the library was built for and what the machine running it offers, stated beside timings so
// that figures from different machines (or builds) can be compared: the kernels' speed depends
// above all on the width of the vector instructions they were compiled for (-march=native).
#pragma once

#include <string>

namespace fastcorot {

// The widest vector instruction set the library was compiled for: "AVX-512", "AVX2", "SSE2", or
// "none" (another architecture, or a build without any).
const char* build_vector_instructions();

// The widest of the same sets this CPU supports ("none" off x86).
const char* cpu_vector_instructions();

// The CPU's model name as the system gives it (Linux: /proc/cpuinfo), or "" where it does not.
std::string cpu_model();

}  // namespace fastcorot
