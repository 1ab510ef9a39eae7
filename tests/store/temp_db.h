// Test helper: a unique database path under the system temp folder, removed (with its -wal and
// -shm companions) when the helper goes out of scope.
//
//   TempDb tmp;                                   // e.g. /tmp/rondo-store-4711-3.db, not created
//   auto db = rondo::store::Store::open(tmp.path());
#pragma once

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "source_dir.h"

namespace rondo::store::testing {

class TempDb {
 public:
  TempDb() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("rondo-store-" + std::to_string(::getpid()) + "-" + std::to_string(counter++) + ".db");
    remove_all_files();
  }
  TempDb(const TempDb&) = delete;
  TempDb& operator=(const TempDb&) = delete;
  ~TempDb() { remove_all_files(); }

  const std::filesystem::path& path() const { return path_; }
  std::string str() const { return path_.string(); }
  std::filesystem::path wal() const { return path_.string() + "-wal"; }

  // Replaces the file with `bytes`.
  void write(std::string_view bytes) const {
    std::ofstream out(path_, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  }

 private:
  void remove_all_files() const {
    std::error_code ec;
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
      std::filesystem::remove_all(path_.string() + suffix, ec);
    }
  }
  std::filesystem::path path_;
};

// The Witham Wharf logs, read in place from the shared data folder.
inline std::filesystem::path witham_dir() {
  return rondo::testing::source_dir() / ".." / "shared" / "data" / "witham_wharf";
}

inline constexpr std::size_t kWithamAttempts = 32078;
inline constexpr std::size_t kWithamSuccesses = 21916;

}  // namespace rondo::store::testing
