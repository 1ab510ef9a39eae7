// Backup and retention of a live store (docs/operations.md).
//
// backup_store copies the database with SQLite's online backup API while other connections (a
// running `rondo serve`) keep reading and writing it: the copy is one consistent snapshot, written
// to FILE.part, checked (PRAGMA integrity_check) and only then renamed to FILE.
//
//   Result<BackupReport> b = backup_store(db, "/backup/rondo-2026-12-02.sqlite");
//
// A PostgreSQL store is backed up with PostgreSQL's pg_dump (custom format, one consistent
// snapshot of the live database) into FILE.part, read back with pg_restore --list, and renamed to
// FILE; pg_restore restores it (docs/operations.md). archive_old_records works on both: the
// archive is an SQLite file either way.
//
// archive_old_records moves what is older than `age` (counted back from the latest time the store
// records, so a simulated run's clock counts, not the machine's) into an archive file, an SQLite
// database with the same tables, and deletes it from the live store: the events that are not about
// a task, the traversals, and the finished tasks (final state, last changed before the cut) with
// all their events. Unfinished tasks and their events always stay. `age` may not be shorter than
// `learning_window` (the executor's refit_window), so the traversals the nightly refit reads stay.
// Running it again is harmless: rows keep their keys and an archived row is never copied twice.
//
//   Result<ArchiveReport> a = archive_old_records(db, days(90), days(14), "rondo-archive.sqlite");
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct BackupReport {
  std::filesystem::path file;
  std::uintmax_t bytes = 0;
  int pages = 0;
};

// Errors: kInvalidInput (FILE exists: a backup never overwrites), kIo/kStorage (cannot write it,
// the copy fails its integrity check).
Result<BackupReport> backup_store(const Store& store, const std::filesystem::path& file);

struct ArchiveReport {
  std::optional<Time> latest;  // the latest time in the store (none: an empty store)
  std::optional<Time> cut;     // records before it were archived
  std::int64_t tasks = 0;      // moved to the archive
  std::int64_t events = 0;
  std::int64_t traversals = 0;
};

// Errors: kInvalidInput (age shorter than learning_window, or the archive file is not an SQLite
// database), kStorage (locked past the busy timeout, disk full). All or nothing in the live store.
Result<ArchiveReport> archive_old_records(Store& store, Duration age, Duration learning_window,
                                          const std::filesystem::path& archive);

}  // namespace rondo::store
