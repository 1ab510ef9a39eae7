// Private to rondo::store: the one INSERT into the event log, shared by the task table (state
// changes) and the event log API, always called inside the caller's open transaction.
#pragma once

#include "db/connection.h"

#include <cstdint>
#include <optional>
#include <string_view>

#include "rondo/store/events.h"

namespace rondo::store {

// Appends one event row and returns its seq; a task event only when its task is stored (nothing
// otherwise). Throws db::Failure (caller's guarded() maps it).
std::optional<std::int64_t> insert_event_row(db::Connection& db, const Event& event);

// insert_event_row where a task event's task must be stored (the transaction has just stored or
// changed it): its absence is a failure, as the foreign key would make it.
inline void append_event_row(db::Connection& db, const Event& event) {
  if (!insert_event_row(db, event)) throw db::Failure(db::FailureKind::kStorage, "the task of an event is not stored");
}

}  // namespace rondo::store
