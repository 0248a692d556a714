// write_file_atomically: a file is either its previous complete content or the new complete one,
// never half-written; the temporary lives beside the file and never survives a failed writer.
// (Killed processes: tests/apps/run_checkpoint_test.cpp injects FASTCOROT_FAULT into the program.)
#include "fastcorot/io/atomic_file.h"

#include "fastcorot/core/error.h"

#include "support/file_bytes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace fastcorot {
namespace {

namespace fs = std::filesystem;

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("fastcorot_atomic_file_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  return names;
}

TEST(AtomicFile, WritesTheWholeFileAndLeavesNothingElse) {
  const fs::path dir = fresh_folder("writes");
  const fs::path path = dir / "frame.vtu";
  write_stream_atomically(path, [](std::ostream& out) { out << "complete"; });
  EXPECT_EQ(testing::read_file_bytes(path), "complete");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"frame.vtu"});
  write_stream_atomically(path, [](std::ostream& out) { out << "replaced"; });
  EXPECT_EQ(testing::read_file_bytes(path), "replaced");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"frame.vtu"});
}

TEST(AtomicFile, WhileWritingTheFinalNameHoldsTheOldContentAndTheTemporaryIsBesideIt) {
  const fs::path dir = fresh_folder("while");
  const fs::path path = dir / "state.json";
  write_stream_atomically(path, [](std::ostream& out) { out << "old"; });
  write_file_atomically(path, [&](const fs::path& temporary) {
    EXPECT_EQ(temporary.parent_path(), path.parent_path());
    EXPECT_EQ(temporary.filename().string().rfind("state.json.partial-", 0), 0u) << temporary;
    std::ofstream(temporary) << "new, half";
    EXPECT_EQ(testing::read_file_bytes(path), "old");  // a reader now sees the old file, whole
  });
  EXPECT_EQ(testing::read_file_bytes(path), "new, half");
}

TEST(AtomicFile, AFailingWriterLeavesThePreviousFileAndNoTemporary) {
  const fs::path dir = fresh_folder("failing");
  const fs::path path = dir / "checkpoint.ckpt";
  write_stream_atomically(path, [](std::ostream& out) { out << "previous"; });
  EXPECT_THROW(write_stream_atomically(path,
                                       [](std::ostream& out) {
                                         out << "half of it";
                                         throw make_error("disk full");
                                       }),
               Error);
  EXPECT_EQ(testing::read_file_bytes(path), "previous");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"checkpoint.ckpt"});
}

TEST(AtomicFile, AFailingFirstWriteLeavesNoFileAtAll) {
  const fs::path dir = fresh_folder("first");
  EXPECT_THROW(write_file_atomically(dir / "a.png",
                                     [](const fs::path& temporary) {
                                       std::ofstream(temporary) << "PNG...";
                                       throw make_error("encoder failed");
                                     }),
               Error);
  EXPECT_TRUE(names_in(dir).empty());
}

TEST(AtomicFile, AMissingFolderIsAnErrorNamingTheFile) {
  const fs::path path = fresh_folder("missing") / "no" / "such" / "folder.vtu";
  try {
    write_stream_atomically(path, [](std::ostream& out) { out << "x"; });
    ADD_FAILURE() << "no error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace fastcorot
