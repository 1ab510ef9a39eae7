// Writing a file so that a reader (or a crash) sees either the old file or the whole new one:
// the bytes go to a temporary file in the same folder, which is synced and then renamed over the
// target, and the folder is synced so that the rename itself survives a power cut.
//
//   if (auto s = write_file_atomically("models.json", json.dump()); !s) return s.error();
//
// On any failure the target is left as it was (or absent) and the temporary file is removed.
#pragma once

#include <filesystem>
#include <string_view>

#include "rondo/core/result.h"

namespace rondo {

// Errors: kIo naming the file and the operating system's reason.
Status write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

}  // namespace rondo
