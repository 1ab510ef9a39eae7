// Opening an SQLite store: the file checks, the connection's pragmas, the schema.
#include <SQLiteCpp/Database.h>

#include <fmt/format.h>

#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>

#include "db/sqlite_connection.h"
#include "migrations.h"
#include "open_backend.h"
#include "store_access.h"

namespace rondo::store {
namespace {

// Every SQLite 3 file starts with these 16 bytes.
constexpr std::string_view kSqliteMagic{"SQLite format 3\0", 16};

// Whether a non-empty file starts like an SQLite database. SQLite itself treats a 1-byte file as
// empty and would overwrite it; we never write over a file that is not already a database.
// A file we cannot read passes: SQLite then reports why it cannot open it.
bool has_sqlite_header(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return true;
  std::string head(kSqliteMagic.size(), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  return in.gcount() == static_cast<std::streamsize>(head.size()) && head == kSqliteMagic;
}

Status check_path(const std::filesystem::path& file, OpenMode mode) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (std::filesystem::is_directory(status)) {
    return Error::invalid(file.string() + ": is a folder, not a database file");
  }
  if (!std::filesystem::exists(status)) {
    if (mode != OpenMode::kCreateIfMissing) return Error::not_found(file.string() + ": no such database file");
    return {};
  }
  // An empty file is a new database to SQLite, and to us.
  if (std::filesystem::is_regular_file(status) && std::filesystem::file_size(file, ec) > 0 && !ec &&
      !has_sqlite_header(file)) {
    return Error::invalid(file.string() + ": not an SQLite database (it does not start with the SQLite header)");
  }
  return {};
}

int busy_timeout_ms(Duration timeout) {
  const auto ms = timeout.count();
  if (ms <= 0) return 0;
  return ms > std::numeric_limits<int>::max() ? std::numeric_limits<int>::max() : static_cast<int>(ms);
}

// Connection settings; see docs/storage.md for why each is what it is.
Status configure(SQLite::Database& db, const std::filesystem::path& file, bool sync_commits) {
  return guarded(file.string(), "setting the connection up", [&]() -> Status {
    const std::string journal = db.execAndGet("PRAGMA journal_mode = WAL").getString();
    if (journal != "wal") {
      return Error::storage(
          fmt::format("{}: cannot switch to WAL journal mode (SQLite kept '{}')", file.string(), journal));
    }
    db.exec(sync_commits ? "PRAGMA synchronous = FULL" : "PRAGMA synchronous = OFF");
    db.exec("PRAGMA foreign_keys = ON");
    if (db.execAndGet("PRAGMA foreign_keys").getInt() != 1) {
      return Error::storage(file.string() + ": this SQLite build cannot enforce foreign keys");
    }
    return {};
  });
}

// SQLite's page cache, per connection: 512 KiB, not SQLite's default of 2000 KiB. The executor's
// reads are small (a task by id, a page of events, the refit's two weeks of traversals once a
// night) and the operating system caches the file anyway; a default-sized cache fills as the
// store grows, which a long-lived service holds as memory for nothing (docs/operations.md, "Memory
// over time": 1 to 2 MiB in the soak). Not stored in the file: set at every open.
constexpr int kPageCacheKiB = 512;

Status limit_page_cache(SQLite::Database& db, const std::filesystem::path& file) {
  return guarded(file.string(), "setting the page cache", [&]() -> Status {
    db.exec(fmt::format("PRAGMA cache_size = -{}", kPageCacheKiB));  // negative: KiB, not pages
    return {};
  });
}

}  // namespace

Result<std::unique_ptr<db::Connection>> open_sqlite(const std::filesystem::path& file, const StoreOptions& options) {
  if (auto ok = check_path(file, options.mode); !ok) return ok.error();
  const bool read_only = options.mode == OpenMode::kReadOnly;
  const int flags =
      read_only ? SQLite::OPEN_READONLY
                : SQLite::OPEN_READWRITE | (options.mode == OpenMode::kCreateIfMissing ? SQLite::OPEN_CREATE : 0);
  std::unique_ptr<db::SqliteConnection> db;
  try {
    db = std::make_unique<db::SqliteConnection>(
        std::make_unique<SQLite::Database>(file, flags, busy_timeout_ms(options.busy_timeout)));
  } catch (const SQLite::Exception& e) {
    return sqlite_error(file, "opening", e);
  }
  // Before any setting is written: a foreign file is refused untouched (not even switched to WAL).
  if (auto ok = check_rondo_store(*db, file.string()); !ok) return ok.error();
  if (auto ok = limit_page_cache(db->raw(), file); !ok) return ok.error();
  if (read_only) {
    if (auto ok = check_readable_schema(*db, file.string()); !ok) return ok.error();
    return std::unique_ptr<db::Connection>(std::move(db));
  }
  if (auto ok = configure(db->raw(), file, options.sync_commits); !ok) return ok.error();
  if (auto ok = migrate(*db, sqlite_migrations(), file.string()); !ok) return ok.error();
  return std::unique_ptr<db::Connection>(std::move(db));
}

}  // namespace rondo::store
