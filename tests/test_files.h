// Files for tests: a fresh folder of the test process's own, and a file's bytes.
//
//   const auto dir = test::fresh_dir("rondo-run-test", "folder");   // /tmp/rondo-run-test-<pid>/folder
//   EXPECT_EQ(test::slurp(dir / "report.json"), expected);
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
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

// `<tmp>/<prefix>-<pid>/<name>`, emptied; created unless `create` is false.
inline std::filesystem::path fresh_dir(const std::string& prefix, const std::string& name, bool create = true) {
  auto dir = std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(::getpid())) / name;
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
