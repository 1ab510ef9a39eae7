// Private to rondo::store: the one INSERT into the event log, shared by the task table (state
// changes) and the event log API, always called inside the caller's open transaction.
#pragma once

#include "db/connection.h"

#include <cstdint>
#include <string_view>

#include "rondo/store/events.h"

namespace rondo::store {

// Appends one event row and returns its seq. Throws db::Failure (caller's guarded() maps it).
std::int64_t insert_event_row(db::Connection& db, const Event& event);

// Whether task `id` is stored. Throws db::Failure.
bool task_exists(db::Connection& db, std::string_view id);

}  // namespace rondo::store
