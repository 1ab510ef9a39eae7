// Private to rondo::store: the few places where SQLite's and PostgreSQL's SQL differ, each a small
// function of the backend, so that the store's SQL is written once. Everything else (ON CONFLICT
// upserts, RETURNING, NULLIF/COALESCE, partial indexes, savepoints) is the same text in both.
//
//   std::string sql = "... WHERE " + as_time(db.backend(), json_field(db.backend(), "task_json",
//                     {"window", "deadline"})) + " > " + as_time(db.backend(), "$3");
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>

#include "db/connection.h"

namespace rondo::store::db {

// The statement that opens a write transaction: SQLite takes the write lock first (BEGIN
// IMMEDIATE, so two writers queue instead of failing later); PostgreSQL locks rows as it writes.
std::string_view begin_write(Backend backend);

// The text of the JSON value at `path` (object keys) in the JSON text column `column`; SQL NULL
// when it is missing or JSON null.
std::string json_field(Backend backend, std::string_view column, std::initializer_list<std::string_view> path);

// `text` (an SQL expression holding an ISO 8601 time, "2026-11-23T08:45:00Z") as a value that
// compares as a time, not as text.
std::string as_time(Backend backend, std::string_view text);

// The store's stamp: which application the database belongs to and its schema version. SQLite
// keeps them in the file header (PRAGMA application_id, user_version); PostgreSQL in the one-row
// table rondo_store. A database without a stamp reads as application 0, version 0. On PostgreSQL
// whether the stamp and other tables exist is read in one statement from pg_catalog (one
// snapshot: a migration committing meanwhile is seen whole or not at all; to_regclass() would
// answer from a cache that a session does not refresh while it takes no lock).
struct Stamp {
  std::int64_t application_id = 0;
  int version = 0;
  bool has_tables = false;  // any table (of its current schema, on PostgreSQL)
};
Stamp read_stamp(Connection& db);
inline int read_schema_version(Connection& db) {
  return read_stamp(db).version;
}
// Inside the migration step's transaction.
void write_stamp(Connection& db, std::int64_t application_id, int version);
// The channel on which PostgreSQL tells that a request was queued (request_watch.h).
inline constexpr std::string_view kRequestChannel = "rondo_requests";
// Inside the transaction that queues request `id`: PostgreSQL NOTIFYs kRequestChannel (delivered at
// the commit); SQLite has nothing to tell.
void notify_request_queued(Connection& db, std::int64_t id);

// Inside a write transaction: waits until no other process migrates this database (SQLite: the
// write lock BEGIN IMMEDIATE took already; PostgreSQL: a transaction-scoped advisory lock).
void lock_for_migration(Connection& db, std::int64_t application_id);

}  // namespace rondo::store::db
