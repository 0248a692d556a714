// Runs a shell command (or the fastcorot executable) and captures its exit status and its standard
// output and error together: the one helper the command-line tests share.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace fastcorot::testing {

struct CommandResult {
  int status;
  std::string output;  // stdout and stderr together
};

inline CommandResult shell(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  CommandResult result{-1, ""};
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe)) result.output += buffer.data();
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

#ifdef FASTCOROT_EXECUTABLE
inline CommandResult run_fastcorot(const std::string& arguments) {
  return shell(std::string(FASTCOROT_EXECUTABLE) + " " + arguments);
}
#endif

}  // namespace fastcorot::testing
