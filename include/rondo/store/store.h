// The rondo database: one SQLite file (WAL mode) holding tasks, the task event log, the traversal
// log and observations. Opening a store sets the connection up and migrates the schema to the
// version this build knows; the table functions (task_table.h, events.h, traversal_log.h,
// observations.h) take the open Store.
//
//   Result<store::Store> db = store::Store::open("run/rondo.db");
//   if (!db) return db.error();               // e.g. "run/rondo.db: not an SQLite database"
//   Status added = store::add_task(*db, record);  // committed when it returns
//
// Layout, pragmas and the schema history are documented in docs/storage.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace SQLite {
class Database;
}

namespace rondo::store {

enum class OpenMode {
  kCreateIfMissing,  // make a new, empty store when the file does not exist (writers, importers)
  kMustExist,        // the file must already exist: kNotFound otherwise (writers that need a store)
  kReadOnly,         // must exist; opened SQLITE_OPEN_READONLY: nothing is created, migrated or
                     // switched (journal mode, pragmas). A store without the current schema is
                     // refused with kInvalidInput naming 'rondo log migrate' (read commands)
};

struct StoreOptions {
  OpenMode mode = OpenMode::kCreateIfMissing;
  // How long a statement waits for another connection's lock before failing with kStorage.
  Duration busy_timeout = seconds(5);
  // True: every commit is synced to disk before it returns (synchronous=FULL), so an accepted task
  // survives a power cut. False (simulated runs, which a seed reproduces): synchronous=OFF, commits
  // still atomic against a crash of the process but not of the machine.
  bool sync_commits = true;
};

// One connection to one database file. Movable, not copyable; closing is the destructor.
// Contract: a Store is used by one thread at a time. Several Stores (in this process or others)
// may open the same file: readers never block the one writer, and writers queue on the lock for
// up to `busy_timeout`.
class Store {
 public:
  // The schema version this build writes (PRAGMA user_version); see docs/storage.md.
  static int latest_schema_version();
  // Heap bytes SQLite holds in this process, over every connection (its page caches, mostly;
  // each connection's cache is bounded by SQLite's cache_size, 2 MB by default).
  static std::int64_t sqlite_memory_bytes();

  // Opens (or creates) `file`, then migrates an older schema, one committed step per version
  // (kReadOnly: never writes; see OpenMode).
  // Errors: kNotFound (kMustExist and no file), kInvalidInput (a folder, not an SQLite file, or an
  // SQLite file that is not a rondo store), kUnsupported (a schema newer than this build),
  // kStorage (locked, corrupt, read-only, disk full).
  static Result<Store> open(const std::filesystem::path& file, const StoreOptions& options = {});

  Store(Store&& other) noexcept;
  Store& operator=(Store&& other) noexcept;
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;
  ~Store();

  const std::filesystem::path& file() const { return file_; }
  // The schema version of the open file (always latest_schema_version() after open()).
  Result<int> schema_version() const;

 private:
  Store(std::filesystem::path file, std::unique_ptr<SQLite::Database> db);
  friend struct StoreAccess;  // src/store: the table functions reach the connection through it

  std::filesystem::path file_;
  std::unique_ptr<SQLite::Database> db_;
};

}  // namespace rondo::store
