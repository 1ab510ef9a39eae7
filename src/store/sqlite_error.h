// Private to rondo::store: the one place where SQLiteCpp's exceptions become rondo::Error values,
// access to a Store's connection, and the integer forms of Time and Duration used in the schema.
//
//   Result<int> n = guarded(store, "counting tasks", [&]() -> Result<int> {
//     return connection(store).execAndGet("SELECT COUNT(*) FROM tasks").getInt();
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

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct StoreAccess {
  static SQLite::Database& db(Store& store) { return *store.db_; }
  static const SQLite::Database& db(const Store& store) { return *store.db_; }
};

inline SQLite::Database& connection(Store& store) {
  return StoreAccess::db(store);
}
inline const SQLite::Database& connection(const Store& store) {
  return StoreAccess::db(store);
}

// The Error for a failed SQLite call on `file` while doing `doing`. The kind follows SQLite's
// result code: "not a database" is bad input (kInvalidInput), everything else kStorage.
Error sqlite_error(const std::filesystem::path& file, std::string_view doing, const SQLite::Exception& e);

// Runs `body` (which returns a Result) and turns any exception it throws into an Error naming the
// store's file and `doing`. Every public function of rondo::store runs its SQL inside one.
template <class Body>
auto guarded(const std::filesystem::path& file, std::string_view doing, Body&& body) -> decltype(body()) {
  try {
    return body();
  } catch (const SQLite::Exception& e) {
    return sqlite_error(file, doing, e);
  } catch (const std::exception& e) {
    return Error::storage(file.string() + ": " + std::string(doing) + ": " + e.what());
  }
}
template <class Body>
auto guarded(const Store& store, std::string_view doing, Body&& body) -> decltype(body()) {
  return guarded(store.file(), doing, std::forward<Body>(body));
}

// Times are stored as integer milliseconds since the Unix epoch, durations as integer milliseconds.
inline std::int64_t to_db(Time t) {
  return static_cast<std::int64_t>(t.time_since_epoch().count());
}
inline std::int64_t to_db(Duration d) {
  return static_cast<std::int64_t>(d.count());
}
inline Time time_from_db(std::int64_t ms) {
  return Time{Duration{ms}};
}
inline Duration duration_from_db(std::int64_t ms) {
  return Duration{ms};
}

}  // namespace rondo::store
