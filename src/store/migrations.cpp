#include "migrations.h"

#include <fmt/format.h>

#include "db/dialect.h"
#include "db/sqlite_connection.h"
#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {
namespace {

// Applies `step` unless another process did meanwhile (the version is read again under the
// migration lock); kInternal if the version found is neither.
Status apply_step(db::Connection& db, const Migration& step, std::string_view name) {
  WriteTx tx(db);
  db::lock_for_migration(db, kApplicationId);
  RONDO_RETURN_IF_ERROR(check_rondo_store(db, name));  // again, under the lock
  const int now = db::read_schema_version(db);
  if (now >= step.version) {
    tx.commit();
    return {};
  }
  if (now != step.version - 1)
    return Error::internal(fmt::format("{}: schema step {} found version {}", name, step.version, now));
  try {
    db.exec_script(step.sql);
  } catch (const db::Failure& f) {
    return failure_error(name, fmt::format("schema step {} ({})", step.version, step.description), f);
  }
  db::write_stamp(db, kApplicationId, step.version);
  tx.commit();
  return {};
}

}  // namespace

std::span<const Migration> schema_migrations(db::Backend backend) {
  return backend == db::Backend::kSqlite ? sqlite_migrations() : pg_migrations();
}

Status check_rondo_store(db::Connection& db, std::string_view name) {
  return guarded(name, "reading the store's stamp", [&]() -> Status {
    const db::Stamp stamp = db::read_stamp(db);
    const std::int64_t app_id = stamp.application_id;
    if (app_id != 0 && app_id != kApplicationId) {
      return Error::invalid(fmt::format("{}: not a rondo database ({} application_id {:#x})", name,
                                        db.backend() == db::Backend::kSqlite ? "SQLite" : "rondo_store",
                                        static_cast<std::uint64_t>(app_id)));
    }
    if (stamp.version == 0 && app_id == 0 && stamp.has_tables) {
      return Error::invalid(fmt::format("{}: not a rondo database ({} with tables but no rondo schema version)", name,
                                        db.backend() == db::Backend::kSqlite ? "an SQLite file" : "a database"));
    }
    return {};
  });
}

Status migrate(db::Connection& db, std::span<const Migration> steps, std::string_view name) {
  const int latest = steps.empty() ? 0 : steps.back().version;
  return guarded(name, "migrating the schema", [&]() -> Status {
    if (auto owned = check_rondo_store(db, name); !owned) return owned;
    const int found = db::read_schema_version(db);
    if (found > latest) {
      return Error{ErrorCode::kUnsupported,
                   fmt::format("{}: schema version {} is newer than this rondo knows ({}); use a newer rondo", name,
                               found, latest)};
    }
    for (const Migration& step : steps) {
      if (step.version <= found) continue;
      RONDO_RETURN_IF_ERROR(apply_step(db, step, name));
    }
    return {};
  });
}

Status check_rondo_file(SQLite::Database& db, const std::filesystem::path& file) {
  db::SqliteConnection connection(db);
  return check_rondo_store(connection, file.string());
}

Status migrate(SQLite::Database& db, std::span<const Migration> steps, const std::filesystem::path& file) {
  db::SqliteConnection connection(db);
  return migrate(connection, steps, file.string());
}

}  // namespace rondo::store
