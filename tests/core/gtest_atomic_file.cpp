#include "rondo/core/atomic_file.h"

#include "test_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace rondo {
namespace {

using test::slurp;

std::filesystem::path fresh_dir() { return test::fresh_dir("rondo-atomic", "files"); }

std::size_t files_in(const std::filesystem::path& dir) {
  std::size_t n = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir)) ++n;
  return n;
}

TEST(AtomicFile, WritesANewFileAndReplacesAnOldOneWhole) {
  const auto dir = fresh_dir();
  ASSERT_TRUE(write_file_atomically(dir / "a.txt", "first").ok());
  EXPECT_EQ(slurp(dir / "a.txt"), "first");
  ASSERT_TRUE(write_file_atomically(dir / "a.txt", std::string(100000, 'x')).ok());
  EXPECT_EQ(slurp(dir / "a.txt"), std::string(100000, 'x'));
  EXPECT_EQ(files_in(dir), 1u);  // no temporary file left behind
  std::filesystem::remove_all(dir);
}

TEST(AtomicFile, AFailureLeavesWhatWasThereAndNoTemporaryFile) {
  const auto dir = fresh_dir();
  std::filesystem::create_directories(dir / "a-folder" / "inside");  // rename cannot replace it
  struct Case {
    std::string name;
    std::filesystem::path target;
  };
  const Case cases[] = {
      {"target is a non-empty folder", dir / "a-folder"},
      {"folder does not exist", dir / "missing" / "a.txt"},
  };
  for (const auto& c : cases) {
    auto s = write_file_atomically(c.target, "new");
    ASSERT_FALSE(s.ok()) << c.name;
    EXPECT_EQ(s.error().code, ErrorCode::kIo) << c.name;
    EXPECT_NE(s.error().message.find(c.target.string()), std::string::npos) << s.error().message;
  }
  EXPECT_TRUE(std::filesystem::is_directory(dir / "a-folder" / "inside"));
  EXPECT_EQ(files_in(dir), 1u);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rondo
