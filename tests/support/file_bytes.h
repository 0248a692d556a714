// Whole files as byte strings, for tests that compare or damage output files.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fastcorot::testing {

inline std::string read_file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

inline void write_file_bytes(const std::filesystem::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

}  // namespace fastcorot::testing
