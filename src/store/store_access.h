// Private to rondo::store: access to a Store's connection, the one place where database failures
// become rondo::Error values, and the integer forms of Time and Duration used in the schema.
//
//   Result<int> n = guarded(store, "counting tasks", [&]() -> Result<int> {
//     return db::query_int64(connection(store), "SELECT COUNT(*) FROM tasks").value_or(0);
//   });
//   // on failure: "run/rondo.db: counting tasks: database is locked" (kStorage)
#pragma once

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Exception.h>

#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

#include "db/connection.h"
#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct StoreAccess {
  static db::Connection& db(const Store& store) { return *store.db_; }
};

// The store's connection. A const Store reads through it too (reads are not writes to the caller).
inline db::Connection& connection(const Store& store) {
  return StoreAccess::db(store);
}

// SQLite's own API of an SQLite store, for what only SQLite has (online backup, ATTACH); null for
// another backend.
SQLite::Database* sqlite_database(const Store& store);

// The Error for a failed database call on `name` (a file or URL) while doing `doing`. Not a
// database, or no connection, is bad input (kInvalidInput); a write the database refused for a stale
// epoch (lease.h) kConflict; everything else kStorage.
Error failure_error(std::string_view name, std::string_view doing, const db::Failure& f);
Error sqlite_error(const std::filesystem::path& file, std::string_view doing, const SQLite::Exception& e);

// Runs `body` (which returns a Result) and turns any exception it throws into an Error naming the
// store and `doing`. Every public function of rondo::store runs its SQL inside one.
template <class Body>
auto guarded(std::string_view name, std::string_view doing, Body&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const db::Failure& f) {
    return failure_error(name, doing, f);
  } catch (const SQLite::Exception& e) {
    return sqlite_error(std::filesystem::path(name), doing, e);
  } catch (const std::exception& e) {
    return Error::storage(std::string(name) + ": " + std::string(doing) + ": " + e.what());
  }
}
template <class Body>
auto guarded(const Store& store, std::string_view doing, Body&& body) -> decltype(body()) {
  return guarded(std::string_view(store.name()), doing, std::forward<Body>(body));
}

// Times are stored as integer milliseconds since the Unix epoch, durations as integer milliseconds.
inline std::int64_t to_db(Time t) {
  return static_cast<std::int64_t>(t.time_since_epoch().count());
}
inline std::int64_t to_db(Duration d) {
  return static_cast<std::int64_t>(d.count());
}
inline std::optional<std::int64_t> to_db(std::optional<Time> t) {
  return t ? std::optional<std::int64_t>(to_db(*t)) : std::nullopt;
}
inline Time time_from_db(std::int64_t ms) {
  return Time{Duration{ms}};
}
inline Duration duration_from_db(std::int64_t ms) {
  return Duration{ms};
}

}  // namespace rondo::store
