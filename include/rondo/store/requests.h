// The queue of requests: what another process (`rondo task add SENTENCE --data DIR`) asks the
// running executive to do, written in one transaction and taken by the executive exactly once.
// A request's body is what `rondo task add --json` prints: a task file ({"timezone", "tasks",
// "routines"}: tasks or routines) or a cancellation ({"cancel": {...}}). Taking a request marks it
// with the time and its outcome in the same transaction that stores its tasks (task_table.h's
// add_tasks), or the event that says what came of it (with the meta entries that keep its routines),
// so a kill never takes a request twice or loses it.
//
//   Result<std::int64_t> id = queue_request(db, {.queued = now, .source = "words", .sentence = s, .body = j});
//   for (const RequestRow& r : *waiting_requests(db)) ...        // not taken yet, oldest first
//   add_tasks(db, rows, "added by words", "added", RequestTaken{r.id, now, "added 2 task(s)"});
//   take_request(db, {r.id, now, "rejected"}, &rejected_event); // the event and the mark, together
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/events.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct RequestRow {
  std::int64_t id = 0;     // assigned by the store: increasing, never reused
  Time queued{};           // when it was queued (the writer's clock)
  std::string source{};    // who queued it: "words" for rondo task add
  std::string sentence{};  // the words, for people (may be empty)
  Json body = Json::object();
  std::optional<Time> taken{};  // when the executive took it; none while it waits
  std::string outcome{};        // what came of it ("added ...", "applied ...", "rejected: ...")
};

// How a request is marked taken, inside the transaction of what taking it stored.
struct RequestTaken {
  std::int64_t id = 0;
  Time at{};
  std::string outcome;  // non-empty
  // Meta entries (robot_state.h) set in the same transaction: what taking it keeps (the routines
  // a request added, for a restart).
  std::vector<std::pair<std::string, std::string>> meta{};
};

// Queues a request (one committed transaction) and returns its id. Errors: kInvalidInput (a body
// that is not a JSON object), kStorage.
Result<std::int64_t> queue_request(Store& store, const RequestRow& request);

// The requests not taken yet, oldest first.
Result<std::vector<RequestRow>> waiting_requests(const Store& store);
// Every request, oldest first.
Result<std::vector<RequestRow>> list_requests(const Store& store);

// Marks a request taken and, when given, appends `event` in the same transaction.
// Errors: kNotFound (no such request), kConflict (already taken: nothing is written), kStorage.
Status take_request(Store& store, const RequestTaken& taken, const Event* event = nullptr);

}  // namespace rondo::store
