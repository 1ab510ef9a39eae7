// Shared by the fuzz targets of issue 14: the invariants every parser keeps (an error is an input
// error with a printable message; output that reaches JSON is valid UTF-8), and a scratch file for
// the readers that take a path.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/core/utf8.h"

namespace rondo::fuzz {

[[noreturn]] inline void broken(const char* what, const std::string& detail) {
  std::fprintf(stderr, "fuzz invariant broken: %s\n%s\n", what, detail.c_str());
  std::abort();
}

// Bad input gives kInvalidInput (or kNotFound for a named file) with a message that is text.
inline void check_error(const Error& e) {
  if (e.code != ErrorCode::kInvalidInput && e.code != ErrorCode::kNotFound) broken("not an input error", e.message);
  if (e.message.empty()) broken("error without a message", "");
  if (first_invalid_utf8(e.message)) broken("message is not UTF-8", replace_invalid_utf8(e.message));
}

// A file holding the input, in a folder of this process's own; `name` is its file name.
inline std::filesystem::path scratch_file(std::string_view name, const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("rondo-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const auto file = dir / std::string(name);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return file;
}

}  // namespace rondo::fuzz
