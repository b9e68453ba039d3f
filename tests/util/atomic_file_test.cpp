#include "knitforge/util/atomic_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "knitforge/util/errors.h"

namespace fs = std::filesystem;
using namespace knitforge;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
fs::path fresh_dir(const char* name) {
  const fs::path d = fs::temp_directory_path() / (std::string(name) + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST(AtomicFile, WritesWholeContent) {
  const fs::path d = fresh_dir("kf_atomic_1");
  const std::string p = (d / "a.txt").string();
  write_file_atomically(p, [](std::ostream& o) { o << "hello\n"; });
  EXPECT_EQ(slurp(p), "hello\n");
  // Replaces an existing file.
  write_file_atomically(p, [](std::ostream& o) { o << "again\n"; });
  EXPECT_EQ(slurp(p), "again\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  fs::remove_all(d);
}

TEST(AtomicFile, FailedWriterLeavesNothingBehind) {
  const fs::path d = fresh_dir("kf_atomic_2");
  const std::string p = (d / "b.txt").string();
  EXPECT_THROW(write_file_atomically(p,
                                     [](std::ostream& o) {
                                       o << "partial";
                                       throw InvalidInput("stop");
                                     }),
               InvalidInput);
  EXPECT_TRUE(fs::is_empty(d));  // neither the target nor a temporary file
  // An existing file is left untouched by a failed write.
  write_file_atomically(p, [](std::ostream& o) { o << "good"; });
  EXPECT_THROW(write_file_atomically(p, [](std::ostream&) { throw IOError("x"); }), IOError);
  EXPECT_EQ(slurp(p), "good");
  EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator()), 1);
  fs::remove_all(d);
}

TEST(AtomicFile, MissingDirectoryIsAnIOErrorNamingThePath) {
  try {
    write_file_atomically("/nonexistent_dir_kf/x.txt", [](std::ostream& o) { o << 1; });
    FAIL() << "expected IOError";
  } catch (const IOError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent_dir_kf/x.txt"), std::string::npos);
  }
}
