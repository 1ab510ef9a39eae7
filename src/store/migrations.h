// Private to rondo::store: the schema history and the runner that brings a database up to date.
// Each Migration takes the schema from version - 1 to version; the runner applies the missing ones
// in order, each in its own committed transaction that also writes the store's stamp (application
// id and version: db/dialect.h), so a crash or an error leaves the database at the last complete
// version. SQLite and PostgreSQL have one history each, with the same versions and the same meaning
// (sqlite_schema.cpp, pg_schema.cpp).
//
//   Status s = migrate(db, schema_migrations(db.backend()), "run/rondo.db");
//
// Never edit a released step: add a new one at the end of both histories (and a test that migrates
// data through it).
#pragma once

#include <SQLiteCpp/Database.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

#include "db/connection.h"
#include "rondo/core/result.h"

namespace rondo::store {

struct Migration {
  int version;                   // the schema version after this step; steps are numbered 1, 2, ...
  std::string_view description;  // one line, for docs and messages
  std::string_view sql;          // one or more statements, run inside the step's transaction
};

// The application id of a rondo store ("rond" in ASCII), written by the first step. A database
// with another application id, or with tables but no schema version, is not ours and is never
// touched.
inline constexpr std::int32_t kApplicationId = 0x726f6e64;

// The steps of the rondo schema, oldest first, for each backend.
std::span<const Migration> sqlite_migrations();
std::span<const Migration> pg_migrations();
std::span<const Migration> schema_migrations(db::Backend backend);
// SQLite's (the embedded default).
inline std::span<const Migration> schema_migrations() {
  return sqlite_migrations();
}

// Refuses databases that are not rondo stores (another application id, or tables without a
// schema version) with kInvalidInput, before anything is written to them. migrate() calls it too.
// `name` names the database (a file or URL) in messages.
Status check_rondo_store(db::Connection& db, std::string_view name);

// Brings `db` to the last version of `steps`.
// Errors: kInvalidInput (not a rondo database), kUnsupported (newer than `steps` know),
// kStorage (a step failed; the database stays at the version before that step).
Status migrate(db::Connection& db, std::span<const Migration> steps, std::string_view name);

// The same on a bare SQLite file (the migration tests).
Status check_rondo_file(SQLite::Database& db, const std::filesystem::path& file);
Status migrate(SQLite::Database& db, std::span<const Migration> steps, const std::filesystem::path& file);

}  // namespace rondo::store
