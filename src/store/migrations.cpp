#include "migrations.h"

#include <SQLiteCpp/Transaction.h>

#include <fmt/format.h>

#include "sqlite_error.h"

namespace rondo::store {
namespace {

// Version 1: the first schema. Times are integer ms since the Unix epoch (UTC), durations integer
// ms. STRICT tables make SQLite enforce the declared column types.
constexpr std::string_view kSchemaV1 = R"sql(
CREATE TABLE tasks (
  id          TEXT    PRIMARY KEY NOT NULL,
  state       TEXT    NOT NULL,
  task_json   TEXT    NOT NULL CHECK (json_valid(task_json)),
  created_ms  INTEGER NOT NULL,
  updated_ms  INTEGER NOT NULL
) STRICT;
CREATE INDEX tasks_by_state ON tasks (state);

CREATE TABLE task_events (
  seq      INTEGER PRIMARY KEY AUTOINCREMENT,
  time_ms  INTEGER NOT NULL,
  task_id  TEXT    NOT NULL REFERENCES tasks (id),
  event    TEXT    NOT NULL,
  reason   TEXT    NOT NULL DEFAULT ''
) STRICT;
CREATE INDEX task_events_by_task ON task_events (task_id, seq);
CREATE TRIGGER task_events_no_update BEFORE UPDATE ON task_events
BEGIN SELECT RAISE(ABORT, 'task_events is append-only'); END;
CREATE TRIGGER task_events_no_delete BEFORE DELETE ON task_events
BEGIN SELECT RAISE(ABORT, 'task_events is append-only'); END;

CREATE TABLE traversals (
  id           INTEGER PRIMARY KEY,
  edge_id      TEXT    NOT NULL,
  from_node    TEXT    NOT NULL,
  to_node      TEXT    NOT NULL,
  start_ms     INTEGER NOT NULL,
  duration_ms  INTEGER NOT NULL CHECK (duration_ms >= 0),
  success      INTEGER NOT NULL CHECK (success IN (0, 1)),
  origin       TEXT    UNIQUE
) STRICT;
CREATE INDEX traversals_by_edge_start ON traversals (edge_id, start_ms);
CREATE INDEX traversals_by_start ON traversals (start_ms);

CREATE TABLE observations (
  id       INTEGER PRIMARY KEY,
  what     TEXT    NOT NULL,
  place    TEXT    NOT NULL,
  time_ms  INTEGER NOT NULL,
  value    REAL    NOT NULL,
  note     TEXT
) STRICT;
CREATE INDEX observations_by_what_place_time ON observations (what, place, time_ms);
)sql";

constexpr Migration kMigrations[] = {
    {1, "tasks, task_events (append-only), traversals, observations", kSchemaV1},
};

int read_user_version(SQLite::Database& db) {
  return db.execAndGet("PRAGMA user_version").getInt();
}

}  // namespace

Status check_rondo_file(SQLite::Database& db, const std::filesystem::path& file) {
  return guarded(file, "reading the file header", [&]() -> Status {
    const int app_id = db.execAndGet("PRAGMA application_id").getInt();
    if (app_id != 0 && app_id != kApplicationId) {
      return Error::invalid(fmt::format("{}: not a rondo database (SQLite application_id {:#x})", file.string(),
                                        static_cast<unsigned>(app_id)));
    }
    if (read_user_version(db) == 0 && app_id == 0 && db.execAndGet("SELECT COUNT(*) FROM sqlite_schema").getInt() > 0) {
      return Error::invalid(fmt::format(
          "{}: not a rondo database (an SQLite file with tables but no rondo schema version)", file.string()));
    }
    return {};
  });
}

std::span<const Migration> schema_migrations() {
  return kMigrations;
}

Status migrate(SQLite::Database& db, std::span<const Migration> steps, const std::filesystem::path& file) {
  const int latest = steps.empty() ? 0 : steps.back().version;
  return guarded(file, "migrating the schema", [&]() -> Status {
    if (auto owned = check_rondo_file(db, file); !owned) return owned;
    const int found = read_user_version(db);
    if (found > latest) {
      return Error{ErrorCode::kUnsupported,
                   fmt::format("{}: schema version {} is newer than this rondo knows ({}); use a newer rondo",
                               file.string(), found, latest)};
    }
    for (const Migration& step : steps) {
      if (step.version <= found) continue;
      // IMMEDIATE takes the write lock first, so two processes opening an old file at once
      // serialise here; the version is read again under the lock and a step already applied by
      // the other one is skipped.
      SQLite::Transaction tx(db, SQLite::TransactionBehavior::IMMEDIATE);
      const int now = read_user_version(db);
      if (now >= step.version) {
        tx.commit();
        continue;
      }
      if (now != step.version - 1) {
        return Error::internal(fmt::format("{}: schema step {} found version {}", file.string(), step.version, now));
      }
      try {
        db.exec(std::string(step.sql));
      } catch (const SQLite::Exception& e) {
        return sqlite_error(file, fmt::format("schema step {} ({})", step.version, step.description), e);
      }
      db.exec(fmt::format("PRAGMA application_id = {}", kApplicationId));
      db.exec(fmt::format("PRAGMA user_version = {}", step.version));
      tx.commit();
    }
    return {};
  });
}

}  // namespace rondo::store
