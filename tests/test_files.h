// Files for tests: a fresh folder of the test process's own, and a file's bytes.
//
//   const auto dir = test::fresh_dir("rondo-run-test", "folder");   // /tmp/rondo-run-test-<pid>/folder
//   EXPECT_EQ(test::slurp(dir / "report.json"), expected);
//
// The process's `<tmp>/<prefix>-<pid>` folders (and any given to remove_at_exit) are removed when
// it exits, unless a test failed: then they are kept to look at.
#pragma once

#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

namespace rondo::test {

// Whether this is the AddressSanitizer build: long scenarios, kill tests and broker or browser
// tests run once, in the normal build, and skip themselves here (the unit tests run in both).
#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kSanitized = true;
#else
inline constexpr bool kSanitized = false;
#endif

namespace detail {

// The folders of fresh_dir() and remove_at_exit() in this process, removed at its exit when no
// test failed.
class RemovedAtExit {
 public:
  void add(const std::filesystem::path& dir) {
    std::lock_guard lock(mutex_);
    dirs_.insert(dir);
  }
  ~RemovedAtExit() {
    // Not in a child that exits without exec (it would remove its parent's files), nor after a
    // failure.
    if (::getpid() != owner_ || ::testing::UnitTest::GetInstance()->Failed()) return;
    std::error_code ec;
    for (const auto& dir : dirs_) std::filesystem::remove_all(dir, ec);
  }

 private:
  std::mutex mutex_;
  std::set<std::filesystem::path> dirs_;
  const pid_t owner_ = ::getpid();
};

inline RemovedAtExit& removed_at_exit() {
  static RemovedAtExit dirs;
  return dirs;
}

}  // namespace detail

// Removes `dir` and what it holds when the test process exits, unless a test failed.
inline void remove_at_exit(const std::filesystem::path& dir) { detail::removed_at_exit().add(dir); }

// `<tmp>/<prefix>-<pid>/<name>`, emptied; created unless `create` is false.
inline std::filesystem::path fresh_dir(const std::string& prefix, const std::string& name, bool create = true) {
  const auto process_dir = std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(::getpid()));
  remove_at_exit(process_dir);
  auto dir = process_dir / name;
  std::filesystem::remove_all(dir);
  if (create) std::filesystem::create_directories(dir);
  return dir;
}

// The whole file as bytes ("" when it cannot be read).
inline std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace rondo::test
