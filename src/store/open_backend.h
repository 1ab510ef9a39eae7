// Private to rondo::store: opening each backend's connection for Store::open (store.cpp): the
// checks before anything is written, the connection's settings, and the schema (migrated, or
// checked for a read-only open).
#pragma once

#include <memory>

#include "db/connection.h"
#include "rondo/core/result.h"
#include "rondo/store/store.h"

namespace rondo::store {

// sqlite_open.cpp
Result<std::unique_ptr<db::Connection>> open_sqlite(const std::filesystem::path& file, const StoreOptions& options);
// pg_open.cpp. connect_postgres: only the connection (the password from the location's file),
// named `application_name` on the server, with libpq's settings and no session settings of ours.
Result<std::unique_ptr<db::Connection>> connect_postgres(const StoreLocation& location,
                                                         std::string_view application_name);
Result<std::unique_ptr<db::Connection>> open_postgres(const StoreLocation& location, const StoreOptions& options);

// A read-only open takes the schema as it is: the current one, or a refusal that says how to get
// it. Nothing is written, so an older store stays as it was.
Status check_readable_schema(db::Connection& db, std::string_view name);

}  // namespace rondo::store
