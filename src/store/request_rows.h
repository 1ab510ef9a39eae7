// Private to rondo::store: marking a queued request taken, inside the caller's open transaction
// (the one that stores the request's tasks, or its rejection's event).
#pragma once

#include "db/connection.h"

#include <string_view>

#include "rondo/core/result.h"
#include "rondo/store/requests.h"

namespace rondo::store {

// kNotFound (no such request), kConflict (already taken). Throws db::Failure.
Status mark_request_taken(db::Connection& db, std::string_view store_name, const RequestTaken& taken);

}  // namespace rondo::store
