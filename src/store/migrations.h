// Private to rondo::store: the schema history and the runner that brings a database up to date.
// Each Migration takes the schema from version - 1 to version; the runner applies the missing ones
// in order, each in its own committed transaction that also sets PRAGMA user_version, so a crash
// or an error leaves the file at the last complete version.
//
//   Status s = migrate(db, schema_migrations(), "run/rondo.db");
//
// Never edit a released step: add a new one at the end (and a test that migrates data through it).
#pragma once

#include <SQLiteCpp/Database.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

#include "rondo/core/result.h"

namespace rondo::store {

struct Migration {
  int version;                   // the user_version after this step; steps are numbered 1, 2, ...
  std::string_view description;  // one line, for docs and messages
  std::string_view sql;          // one or more statements, run inside the step's transaction
};

// PRAGMA application_id of a rondo store ("rond" in ASCII), written by the first step. A file with
// another application id, or with tables but no schema version, is not ours and is never touched.
inline constexpr std::int32_t kApplicationId = 0x726f6e64;

// The steps of the rondo schema, oldest first.
std::span<const Migration> schema_migrations();

// Refuses files that are SQLite but not rondo stores (another application id, or tables without a
// schema version) with kInvalidInput, before anything is written to them. migrate() calls it too.
Status check_rondo_file(SQLite::Database& db, const std::filesystem::path& file);

// Brings `db` to the last version of `steps`. `file` names the database in messages.
// Errors: kInvalidInput (not a rondo database), kUnsupported (newer than `steps` know),
// kStorage (a step failed; the file stays at the version before that step).
Status migrate(SQLite::Database& db, std::span<const Migration> steps, const std::filesystem::path& file);

}  // namespace rondo::store
