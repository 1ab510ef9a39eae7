// Private to rondo::store: marking a queued request taken, inside the caller's open transaction
// (the one that stores the request's tasks, or its rejection's event).
#pragma once

#include <SQLiteCpp/Database.h>

#include <filesystem>

#include "rondo/core/result.h"
#include "rondo/store/requests.h"

namespace rondo::store {

// kNotFound (no such request), kConflict (already taken). Throws SQLite::Exception.
Status mark_request_taken(SQLite::Database& db, const std::filesystem::path& file, const RequestTaken& taken);

}  // namespace rondo::store
