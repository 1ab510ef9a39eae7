#include "sqlite_error.h"

#include <sqlite3.h>

#include <fmt/format.h>

namespace rondo::store {

Error sqlite_error(const std::filesystem::path& file, std::string_view doing, const SQLite::Exception& e) {
  const int primary = e.getErrorCode() & 0xff;
  if (primary == SQLITE_NOTADB) {
    return Error::invalid(fmt::format("{}: not an SQLite database ({})", file.string(), e.what()));
  }
  if (primary == SQLITE_CORRUPT) {
    return Error::storage(fmt::format("{}: {}: the database file is corrupt ({})", file.string(), doing, e.what()));
  }
  return Error::storage(fmt::format("{}: {}: {}", file.string(), doing, e.what()));
}

}  // namespace rondo::store
