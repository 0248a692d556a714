// Files that are never seen half-written. Every output file of fastcorot (VTU frames, ParaView
// collections, state dumps, pictures, checkpoints) is written to a temporary file beside its final
// name (`NAME.partial-PID`, same folder so that the rename stays on one file system), flushed to
// disk (fsync), then renamed over NAME (POSIX rename is atomic), and the folder is synced. A run
// that is killed or fails while writing leaves NAME as it was before (absent, or its previous
// complete content) and at most a `.partial-PID` file; a writer that throws leaves neither.
//
// Fault injection for tests: the environment variable FASTCOROT_FAULT makes the N-th atomic write
// of the process (counted from 1) fail:
//   FASTCOROT_FAULT=write-error:N  throws fastcorot::Error as a full disk would (temporary
//   removed); FASTCOROT_FAULT=write-kill:N   truncates the temporary file to half its size and
//   kills the
//                                  process with SIGKILL before the rename, as an interruption
//                                  would.
// Any other value is an error naming the variable.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>

namespace fastcorot {

// Calls write(temporary), which must create and fill the file `temporary`, then makes it `path` as
// described above. Errors (from `write` or the file system) propagate as fastcorot::Error naming
// `path`, after removing the temporary file.
void write_file_atomically(
    const std::filesystem::path& path,
    const std::function<void(const std::filesystem::path& temporary)>& write);

// The same for writers to a stream: `write` fills `out`; a failed stream is an error naming `path`.
void write_stream_atomically(const std::filesystem::path& path,
                             const std::function<void(std::ostream& out)>& write);

}  // namespace fastcorot
