#include "store_access.h"

#include <sqlite3.h>

#include <fmt/format.h>

#include "db/sqlite_connection.h"

namespace rondo::store {

SQLite::Database* sqlite_database(const Store& store) {
  auto* sqlite = dynamic_cast<db::SqliteConnection*>(&connection(store));
  return sqlite ? &sqlite->raw() : nullptr;
}

Error failure_error(std::string_view name, std::string_view doing, const db::Failure& f) {
  switch (f.kind()) {
    case db::FailureKind::kNotADatabase:
      return Error::invalid(fmt::format("{}: not an SQLite database ({})", name, f.what()));
    case db::FailureKind::kCorrupt:
      return Error::storage(fmt::format("{}: {}: the database is corrupt ({})", name, doing, f.what()));
    case db::FailureKind::kUnreachable:
      return Error::invalid(fmt::format("{}: {}: cannot connect: {}", name, doing, f.what()));
    case db::FailureKind::kFenced:
      return Error{ErrorCode::kConflict, fmt::format("{}: {}: {}", name, doing, f.what())};
    case db::FailureKind::kStorage:
      break;
  }
  return Error::storage(fmt::format("{}: {}: {}", name, doing, f.what()));
}

Error sqlite_error(const std::filesystem::path& file, std::string_view doing, const SQLite::Exception& e) {
  return failure_error(file.string(), doing, db::sqlite_failure(e));
}

}  // namespace rondo::store
