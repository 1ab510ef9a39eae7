#include "rondo/store/store.h"

#include <sqlite3.h>

#include <fmt/format.h>

#include "db/dialect.h"
#include "migrations.h"
#include "open_backend.h"
#include "store_access.h"

namespace rondo::store {

int Store::latest_schema_version() {
  return sqlite_migrations().back().version;
}

std::int64_t Store::sqlite_memory_bytes() { return sqlite3_memory_used(); }

Status check_readable_schema(db::Connection& db, std::string_view name) {
  return guarded(name, "reading the schema version", [&]() -> Status {
    const int found = db::read_schema_version(db);
    const int latest = Store::latest_schema_version();
    if (found == 0) {
      return Error::invalid(
          fmt::format("{}: an empty database, not yet a rondo store (nothing to read; 'rondo log import' makes one)",
                      name));
    }
    if (found > latest) {
      return Error{ErrorCode::kUnsupported,
                   fmt::format("{}: schema version {} is newer than this rondo knows ({}); use a newer rondo", name,
                               found, latest)};
    }
    if (found < latest) {
      return Error::invalid(fmt::format(
          "{}: schema version {} is older than this rondo's {}, and read-only commands never change a store: "
          "run 'rondo log migrate --db {}' first",
          name, found, latest, name));
    }
    return {};
  });
}

Result<Store> Store::open(const std::filesystem::path& file, const StoreOptions& options) {
  return open(StoreLocation::sqlite(file), options);
}

Result<Store> Store::open(const StoreLocation& location, const StoreOptions& options) {
  if (location.kind == StoreLocation::Kind::kSqlite) {
    RONDO_ASSIGN_OR_RETURN(std::unique_ptr<db::Connection> db, open_sqlite(location.file, options));
    return Store(location, std::move(db));
  }
  RONDO_ASSIGN_OR_RETURN(std::unique_ptr<db::Connection> db, open_postgres(location, options));
  return Store(location, std::move(db));
}

Result<Store> Store::open_named(std::string_view name, const StoreOptions& options) {
  RONDO_ASSIGN_OR_RETURN(const StoreLocation location, StoreLocation::parse(name));
  return open(location, options);
}

Store::Store(StoreLocation location, std::unique_ptr<db::Connection> db)
    : location_(std::move(location)), name_(location_.name()), db_(std::move(db)) {}
Store::Store(Store&& other) noexcept = default;
Store& Store::operator=(Store&& other) noexcept = default;
Store::~Store() = default;

Result<int> Store::schema_version() const {
  return guarded(*this, "reading the schema version", [&]() -> Result<int> { return db::read_schema_version(*db_); });
}

}  // namespace rondo::store
