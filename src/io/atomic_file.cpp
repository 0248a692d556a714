#include "fastcorot/io/atomic_file.h"

#include "fastcorot/core/error.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

namespace fastcorot {

namespace {

struct Fault {
  enum class Kind { none, error, kill } kind = Kind::none;
  long at = 0;
};

// FASTCOROT_FAULT, read once per process.
const Fault& injected_fault() {
  static const Fault fault = [] {
    Fault parsed;
    const char* text = std::getenv("FASTCOROT_FAULT");
    if (!text || !*text) return parsed;
    const std::string value = text;
    const auto colon = value.find(':');
    const std::string kind = value.substr(0, colon);
    char* end = nullptr;
    const long at =
        colon == std::string::npos ? 0 : std::strtol(value.c_str() + colon + 1, &end, 10);
    if ((kind != "write-error" && kind != "write-kill") || at < 1 || *end != '\0') {
      throw make_error("FASTCOROT_FAULT=\"", value,
                       "\": expected write-error:N or write-kill:N with N >= 1");
    }
    parsed.kind = kind == "write-error" ? Fault::Kind::error : Fault::Kind::kill;
    parsed.at = at;
    return parsed;
  }();
  return fault;
}

std::atomic<long> atomic_writes{0};

void sync_path(const std::filesystem::path& path, int flags, const std::filesystem::path& named) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) throw make_error(named.string(), ": cannot open to sync: ", std::strerror(errno));
  const int result = ::fsync(fd);
  const int error = errno;
  ::close(fd);
  if (result != 0)
    throw make_error(named.string(), ": cannot sync to disk: ", std::strerror(error));
}

void apply_fault(const std::filesystem::path& temporary, const std::filesystem::path& path,
                 long write_number) {
  const Fault& fault = injected_fault();
  if (fault.kind == Fault::Kind::none || write_number != fault.at) return;
  if (fault.kind == Fault::Kind::error) {
    throw make_error(path.string(),
                     ": cannot write: injected fault (FASTCOROT_FAULT=write-error:", fault.at, ")");
  }
  std::error_code ignored;
  const auto size = std::filesystem::file_size(temporary, ignored);
  if (!ignored) std::filesystem::resize_file(temporary, size / 2, ignored);
  std::raise(SIGKILL);
}

}  // namespace

void write_file_atomically(
    const std::filesystem::path& path,
    const std::function<void(const std::filesystem::path& temporary)>& write) {
  const long write_number = ++atomic_writes;
  const std::filesystem::path folder =
      path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  std::filesystem::path temporary = path;
  temporary += ".partial-" + std::to_string(::getpid());
  try {
    write(temporary);
    apply_fault(temporary, path, write_number);
    sync_path(temporary, O_RDONLY, path);
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
      throw make_error(path.string(), ": cannot rename the finished temporary file onto it: ",
                       std::strerror(errno));
    }
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  // The rename itself reaches the disk with the folder's entry.
  sync_path(folder, O_RDONLY | O_DIRECTORY, path);
}

void write_stream_atomically(const std::filesystem::path& path,
                             const std::function<void(std::ostream& out)>& write) {
  write_file_atomically(path, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw make_error(path.string(), ": cannot open for writing: ", std::strerror(errno));
    write(out);
    out.close();
    if (!out) throw make_error(path.string(), ": write error (disk full?)");
  });
}

}  // namespace fastcorot
