// A process that keeps one core busy (a shell loop) for as long as the object lives, as another
// program beside a simulation would: for tests of how parallel loops behave on a loaded machine.
#pragma once

#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stdexcept>

namespace fastcorot::testing {

class BusyCore {
 public:
  BusyCore() {
    char sh[] = "/bin/sh";
    char flag[] = "-c";
    char loop[] = "while :; do :; done";
    char* argv[] = {sh, flag, loop, nullptr};
    if (posix_spawn(&pid_, sh, nullptr, nullptr, argv, environ) != 0) throw std::runtime_error("cannot start /bin/sh");
  }
  ~BusyCore() {
    kill(pid_, SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
  BusyCore(const BusyCore&) = delete;
  BusyCore& operator=(const BusyCore&) = delete;

 private:
  pid_t pid_ = -1;
};

}  // namespace fastcorot::testing
