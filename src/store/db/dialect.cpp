#include "db/dialect.h"

#include <fmt/format.h>

namespace rondo::store::db {

std::string_view begin_write(Backend backend) {
  return backend == Backend::kSqlite ? "BEGIN IMMEDIATE" : "BEGIN";
}

std::string json_field(Backend backend, std::string_view column, std::initializer_list<std::string_view> path) {
  if (backend == Backend::kSqlite) {
    std::string where = "$";
    for (std::string_view key : path) where += fmt::format(".{}", key);
    return fmt::format("json_extract({}, '{}')", column, where);
  }
  std::string keys;
  for (std::string_view key : path) keys += (keys.empty() ? "" : ",") + std::string(key);
  return fmt::format("({} #>> '{{{}}}')", column, keys);
}

std::string as_time(Backend backend, std::string_view text) {
  if (backend == Backend::kSqlite) return fmt::format("julianday({})", text);
  return fmt::format("CAST({} AS timestamptz)", text);
}

Stamp read_stamp(Connection& db) {
  Stamp stamp;
  if (db.backend() == Backend::kSqlite) {
    stamp.application_id = query_int64(db, "PRAGMA application_id").value_or(0);
    stamp.version = static_cast<int>(query_int64(db, "PRAGMA user_version").value_or(0));
    stamp.has_tables = query_int64(db, "SELECT COUNT(*) FROM sqlite_schema").value_or(0) > 0;
    return stamp;
  }
  auto tables = db.query(
      "SELECT COUNT(*), COUNT(*) FILTER (WHERE tablename = 'rondo_store') FROM pg_catalog.pg_tables "
      "WHERE schemaname = current_schema()");
  if (!tables->next()) return stamp;
  stamp.has_tables = tables->int64(0) > 0;
  if (tables->int64(1) == 0) return stamp;
  auto row = db.query("SELECT application_id, schema_version FROM rondo_store");
  if (!row->next()) return stamp;
  stamp.application_id = row->int64(0);
  stamp.version = static_cast<int>(row->int64(1));
  return stamp;
}

void write_stamp(Connection& db, std::int64_t application_id, int version) {
  if (db.backend() == Backend::kSqlite) {
    db.exec_script(fmt::format("PRAGMA application_id = {}; PRAGMA user_version = {}", application_id, version));
    return;
  }
  db.exec_script(
      "CREATE TABLE IF NOT EXISTS rondo_store (one BOOLEAN PRIMARY KEY DEFAULT TRUE CHECK (one), "
      "application_id BIGINT NOT NULL, schema_version INTEGER NOT NULL)");
  db.exec(
      "INSERT INTO rondo_store (application_id, schema_version) VALUES ($1, $2) ON CONFLICT (one) DO UPDATE "
      "SET application_id = excluded.application_id, schema_version = excluded.schema_version",
      {application_id, version});
}

void notify_request_queued(Connection& db, std::int64_t id) {
  if (db.backend() == Backend::kPostgres)
    (void)db.query("SELECT pg_notify($1, $2)", {std::string(kRequestChannel), std::to_string(id)})->next();
}

void lock_for_migration(Connection& db, std::int64_t application_id) {
  if (db.backend() == Backend::kPostgres) (void)db.query("SELECT pg_advisory_xact_lock($1)", {application_id})->next();
}

}  // namespace rondo::store::db
