// Opening a PostgreSQL store: the password, the connection and its session settings, the schema.
#include <fmt/format.h>

#include <fstream>
#include <string>

#include "db/dialect.h"
#include "db/pg_connection.h"
#include "migrations.h"
#include "open_backend.h"
#include "store_access.h"

namespace rondo::store {
namespace {

// The password on the first line of `file` (a trailing newline or carriage return is not part of it).
Result<std::string> read_password_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return Error::invalid(fmt::format("{}: password_file: cannot read it", file.string()));
  std::string line;
  std::getline(in, line);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line.empty()) return Error::invalid(fmt::format("{}: password_file: the first line is empty", file.string()));
  return line;
}

// lock_timeout plays SQLite's busy timeout: how long a statement waits for another's lock;
// statement_timeout bounds a statement's whole run (0: none).
// synchronous_commit off is SQLite's synchronous=OFF: a commit is atomic, not yet on disk.
void configure(db::Connection& db, const StoreOptions& options) {
  db.exec_script(fmt::format(
      "SET lock_timeout = {}; SET statement_timeout = {}; SET synchronous_commit = {}; SET client_min_messages = warning",
      std::max<std::int64_t>(options.busy_timeout.count(), 1), std::max<std::int64_t>(options.statement_timeout.count(), 0),
      options.sync_commits ? "on" : "off"));
  if (options.mode == OpenMode::kReadOnly) db.exec_script("SET default_transaction_read_only = on");
}

}  // namespace

Result<std::unique_ptr<db::Connection>> connect_postgres(const StoreLocation& location,
                                                         std::string_view application_name) {
  db::PgAddress address{.conninfo = location.url, .password = std::nullopt};
  address.application_name = std::string(application_name);
  if (location.password_file) {
    RONDO_ASSIGN_OR_RETURN(address.password, read_password_file(*location.password_file));
  }
  try {
    return std::unique_ptr<db::Connection>(db::PgConnection::connect(address));
  } catch (const db::Failure& f) {
    return failure_error(location.name(), "opening", f);
  }
}

Result<std::unique_ptr<db::Connection>> open_postgres(const StoreLocation& location, const StoreOptions& options) {
  const std::string name = location.name();
  RONDO_ASSIGN_OR_RETURN(std::unique_ptr<db::Connection> db, connect_postgres(location, "rondo"));
  RONDO_RETURN_IF_ERROR(guarded(std::string_view(name), "setting the session up", [&]() -> Status {
    configure(*db, options);
    return {};
  }));
  RONDO_RETURN_IF_ERROR(check_rondo_store(*db, name));
  if (options.mode == OpenMode::kMustExist || options.mode == OpenMode::kReadOnly) {
    const Result<int> version = guarded(std::string_view(name), "reading the schema version",
                                        [&]() -> Result<int> { return db::read_schema_version(*db); });
    if (!version) return version.error();
    if (*version == 0) return Error::not_found(fmt::format("{}: the database holds no rondo store yet", name));
  }
  if (options.mode == OpenMode::kReadOnly) {
    RONDO_RETURN_IF_ERROR(check_readable_schema(*db, name));
    return db;
  }
  RONDO_RETURN_IF_ERROR(migrate(*db, pg_migrations(), name));
  return db;
}

}  // namespace rondo::store
