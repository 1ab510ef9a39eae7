// backup_store: SQLite's online backup API into FILE.part, checked, then renamed (backup.h).
#include <fmt/format.h>
#include <sqlite3.h>

#include <chrono>
#include <system_error>
#include <thread>

#include "rondo/store/backup.h"
#include "pg_backup.h"
#include "store_access.h"

namespace rondo::store {
namespace {

// Closes the destination connection on every path out.
struct Destination {
  sqlite3* db = nullptr;
  ~Destination() { sqlite3_close(db); }
};

Status check_copy(const std::filesystem::path& file) {
  auto copy = Store::open(file, {.mode = OpenMode::kReadOnly});
  if (!copy) return Error::storage(fmt::format("{}: the copy cannot be opened: {}", file.string(), copy.error().message));
  return guarded(*copy, "checking the copy", [&]() -> Status {
    const std::string verdict = db::query_text(connection(*copy), "PRAGMA integrity_check").value_or("");
    if (verdict != "ok") return Error::storage(fmt::format("{}: the copy fails its integrity check: {}", file.string(), verdict));
    return Status{};
  });
}

}  // namespace

Result<BackupReport> backup_store(const Store& store, const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::exists(file, ec))
    return Error::invalid(fmt::format("{}: exists already (a backup never overwrites; name another file)", file.string()));
  SQLite::Database* source = sqlite_database(store);
  if (source == nullptr) return pg_dump_store(store.location(), file);
  std::filesystem::path part = file;
  part += ".part";
  std::filesystem::remove(part, ec);  // left by an interrupted backup

  BackupReport report{.file = file};
  {
    Destination dest;
    if (sqlite3_open_v2(part.c_str(), &dest.db, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK)
      return Error::io(fmt::format("{}: cannot create the backup: {}", part.string(), sqlite3_errmsg(dest.db)));
    sqlite3_backup* b = sqlite3_backup_init(dest.db, "main", source->getHandle(), "main");
    if (b == nullptr)
      return Error::storage(fmt::format("{}: cannot start the backup: {}", store.name(), sqlite3_errmsg(dest.db)));
    // A few hundred pages per step: the writer of a live store is never held up for long. Busy or
    // locked steps are tried again (a writer in WAL mode does not block the reader, so this is rare).
    int rc = SQLITE_OK;
    while (rc == SQLITE_OK || rc == SQLITE_BUSY || rc == SQLITE_LOCKED) {
      rc = sqlite3_backup_step(b, 256);
      if (rc == SQLITE_BUSY || rc == SQLITE_LOCKED) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    report.pages = sqlite3_backup_pagecount(b);
    sqlite3_backup_finish(b);
    if (rc != SQLITE_DONE) {
      const std::string why = sqlite3_errstr(rc);
      std::filesystem::remove(part, ec);
      return Error::storage(fmt::format("{}: the backup to {} failed: {}", store.name(), part.string(), why));
    }
    // A backup is one self-contained file: out of WAL mode (the store switches back on open).
    if (sqlite3_exec(dest.db, "PRAGMA journal_mode = DELETE", nullptr, nullptr, nullptr) != SQLITE_OK)
      return Error::storage(fmt::format("{}: cannot finish the backup: {}", part.string(), sqlite3_errmsg(dest.db)));
  }
  if (Status ok = check_copy(part); !ok) {
    std::filesystem::remove(part, ec);
    return ok.error();
  }
  std::filesystem::rename(part, file, ec);
  if (ec) return Error::io(fmt::format("{}: cannot rename the finished backup: {}", file.string(), ec.message()));
  report.bytes = std::filesystem::file_size(file, ec);
  return report;
}

}  // namespace rondo::store
