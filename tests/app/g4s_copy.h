// A copy of the G4S example in a test's folder, to edit: a file's text replaced in place, and the
// line where a text stands (for errors that name file:line).
//
//   const auto deployment = test::copy_g4s(dir);
//   test::replace_in(dir / "routines.yaml", "every: 3h", "every: 30s");
//   EXPECT_THAT(err, HasSubstr("routines.yaml:" + std::to_string(test::line_of(text, "every: 30s"))));
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "test_files.h"

namespace rondo::test {

// The G4S example's five files copied into `dir`; its deployment file.
inline std::filesystem::path copy_g4s(const std::filesystem::path& dir) {
  for (const char* f : {"deployment.yaml", "map.yaml", "routines.yaml", "world.yaml", "requests.yaml"})
    std::filesystem::copy_file(std::filesystem::path("examples/g4s") / f, dir / f);
  return dir / "deployment.yaml";
}

// Replaces the first `from` in `file` by `to` (a test failure when `from` is not there).
inline void replace_in(const std::filesystem::path& file, const std::string& from, const std::string& to) {
  std::string text = slurp(file);
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << file.filename().string() << " has no '" << from << "'";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

// The 1-based line of the first `needle` in `text`; -1 when it is not there.
inline int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  return at == std::string::npos
             ? -1
             : 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

}  // namespace rondo::test
