// The rondo database, holding tasks, the event log, the traversal log and observations: one SQLite
// file (WAL mode; the embedded default) or a PostgreSQL database (a fleet's shared store). Opening a
// store sets the connection up and migrates the schema to the version this build knows; the table
// functions (task_table.h, events.h, traversal_log.h, observations.h) take the open Store and
// behave the same on both backends.
//
//   Result<store::Store> db = store::Store::open("run/rondo.db");
//   if (!db) return db.error();               // e.g. "run/rondo.db: not an SQLite database"
//   Status added = store::add_task(*db, record);  // committed when it returns
//
//   auto where = store::StoreLocation::parse("postgresql://rondo@db.example/rondo");
//   Result<store::Store> pg = store::Store::open(*where);  // the password: PGPASSWORD, ~/.pgpass
//
// Layout, pragmas and the schema history are documented in docs/storage.md.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo::store {

namespace db {
class Connection;
}

// Where a store lives: an SQLite file, or a PostgreSQL database named by a libpq connection string.
// A password is never part of the URL (it would show in process lists, shell histories and logs):
// it comes from `password_file` (its first line), or libpq's own ways (PGPASSWORD, PGPASSFILE,
// ~/.pgpass).
struct StoreLocation {
  enum class Kind { kSqlite, kPostgres };
  Kind kind = Kind::kSqlite;
  std::filesystem::path file;                          // kSqlite
  std::string url;                                     // kPostgres: "postgresql://user@host:port/db?..."
  std::optional<std::filesystem::path> password_file;  // kPostgres

  static StoreLocation sqlite(std::filesystem::path file);
  // Errors (kInvalidInput): a URL libpq cannot parse, or one that holds a password.
  static Result<StoreLocation> postgres(std::string url, std::optional<std::filesystem::path> password_file = {});
  // A store as a person names it: "postgresql://..." or "postgres://..." is PostgreSQL, anything
  // else the path of an SQLite file.
  static Result<StoreLocation> parse(std::string_view text);

  // For messages: the file, or the URL.
  std::string name() const;
};

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
  // PostgreSQL: the longest a statement may run on the server before it is cancelled (kStorage
  // "canceling statement due to statement timeout"), so that a stuck statement cannot hold the
  // executor's thread for good; 0: no limit. SQLite's statements are local: no limit there.
  Duration statement_timeout = seconds(60);
};

// One connection to one database. Movable, not copyable; closing is the destructor.
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
  // The same for either backend. On PostgreSQL the database must exist (an empty one becomes a
  // store, unless kMustExist, which needs a rondo store in it: kNotFound), and a server that cannot
  // be reached within the connect timeout (5 s, or the URL's connect_timeout) is kInvalidInput
  // naming the URL and libpq's reason. kReadOnly opens a read-only session.
  static Result<Store> open(const StoreLocation& location, const StoreOptions& options = {});
  // A store as a person names it (StoreLocation::parse: a postgresql:// URL or a file), e.g. --db.
  static Result<Store> open_named(std::string_view name, const StoreOptions& options = {});

  Store(Store&& other) noexcept;
  Store& operator=(Store&& other) noexcept;
  Store(const Store&) = delete;
  Store& operator=(const Store&) = delete;
  ~Store();

  // The SQLite file (empty for PostgreSQL).
  const std::filesystem::path& file() const { return location_.file; }
  const StoreLocation& location() const { return location_; }
  // The store in messages: the file, or the URL.
  const std::string& name() const { return name_; }
  bool is_postgres() const { return location_.kind == StoreLocation::Kind::kPostgres; }
  // The schema version of the open store (always latest_schema_version() after open()).
  Result<int> schema_version() const;

 private:
  Store(StoreLocation location, std::unique_ptr<db::Connection> db);
  friend struct StoreAccess;  // src/store: the table functions reach the connection through it

  StoreLocation location_;
  std::string name_;
  std::unique_ptr<db::Connection> db_;
};

}  // namespace rondo::store
