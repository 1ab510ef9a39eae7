// Private to rondo::store: backup_store's PostgreSQL half (backup.h), with PostgreSQL's tools.
#pragma once

#include <filesystem>

#include "rondo/store/backup.h"
#include "rondo/store/store.h"

namespace rondo::store {

// pg_dump --format=custom of `location` into FILE.part, checked with pg_restore --list, renamed to
// FILE. The tools are found on PATH; the password comes from the location's password_file (as
// PGPASSWORD in their environment) or libpq's usual ways. Errors: kStorage (a tool failed: its
// first line of output), kIo. FILE must not exist (backup_store checks).
Result<BackupReport> pg_dump_store(const StoreLocation& location, const std::filesystem::path& file);

}  // namespace rondo::store
