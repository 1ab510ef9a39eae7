// The tasks the executive has accepted, each with its current state. A task is stored as the JSON
// text its codec writes (rondo::Json), so the store does not change when Task gains fields; every
// state change also appends to the event log (events.h) in the same transaction. A task's
// progress (how far a restartable task got: the actions done, what is on board) is a JSON value
// that the executor owns.
//
//   TaskRow r{.id = "t1", .task = task_json, .state = "queued", .created = now, .updated = now};
//   if (Status s = add_task(db, r); !s) return s.error();   // durable once this returns
//   Status s = set_task_state(db, "t1", "navigating", later, "scheduled start");
//   Result<TaskRow> back = get_task(db, "t1");           // state "navigating", updated later
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/requests.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct TaskRow {
  std::string id;     // unique in the store
  Json task;          // the task as its JSON codec writes it
  std::string state;  // the life-cycle state, e.g. "queued", "navigating", "succeeded"
  Time created;       // when the task was accepted
  Time updated;       // the last state change
  std::string source{};            // who added it: "routine", "request", "api", ...
  Json progress = Json(nullptr);   // the executor's record of what is done; null before anything is
  // When it was planned to start and end at its latest state change (set_task_state); none when
  // it was not planned then.
  std::optional<Time> planned_start{}, planned_end{};
  // The robot the task is allocated to (a fleet's); empty: none. Its state-change events name it.
  std::string robot{};

  bool operator==(const TaskRow&) const = default;
};

// When a task is planned to start and end (the latest schedule's); both unset when it is not.
struct PlannedTimes {
  std::optional<Time> start{}, end{};
};

// Accepts a new task: stores `task` and appends the event (task.created, task.id, task.state,
// `reason`) in one transaction, committed (synchronous=FULL: on disk) before this returns, so a
// crash right after never loses it. Errors: kInvalidInput (the id is already stored, or it is
// empty), kStorage.
Status add_task(Store& store, const TaskRow& task, std::string_view reason = "accepted", std::string_view code = "");

// Accepts several tasks at once, all or nothing: one transaction, one sync. If any id is empty,
// already stored or repeated in `tasks`, nothing is stored. With `taken`, the queued request the
// tasks come from is marked taken in the same transaction (requests.h; kConflict when it already
// is, and nothing is stored). Errors as add_task's.
Status add_tasks(Store& store, std::span<const TaskRow> tasks, std::string_view reason = "accepted",
                 std::string_view code = "", const RequestTaken* taken = nullptr);

// Moves task `id` to `state` at time `at` and appends the event (at, id, state, code, reason), in
// one transaction; with `planned`, also records when it is planned to start and end (the row's
// planned_start and planned_end). Errors: kNotFound (no such task), kStorage.
Status set_task_state(Store& store, std::string_view id, std::string_view state, Time at, std::string_view reason,
                      std::string_view code = "", const std::optional<PlannedTimes>& planned = std::nullopt);

// Replaces task `id`'s progress. Errors: kNotFound (no such task), kStorage.
Status set_task_progress(Store& store, std::string_view id, const Json& progress);

// Replaces task `id`'s definition (its window or priority changed while it waits; the executor
// appends the event that says so). Errors: kNotFound (no such task), kStorage.
Status set_task_definition(Store& store, std::string_view id, const Json& task);

// Allocates a stored task to `robot` ('' : to none). Errors: kNotFound, kStorage.
Status set_task_robot(Store& store, std::string_view id, std::string_view robot);

// Errors: kNotFound (no such task), kStorage (including stored JSON that no longer parses).
Result<TaskRow> get_task(const Store& store, std::string_view id);

// Every stored task, in the order they were accepted (created time, then id).
Result<std::vector<TaskRow>> list_tasks(const Store& store);
// The tasks whose current state is `state`, in the order they were accepted.
Result<std::vector<TaskRow>> list_tasks_in_state(const Store& store, std::string_view state);

// A page of the stored tasks, in the order they were accepted (rowid order, also within a batch),
// that pass every filter given: their state, their source, a window overlapping [from, to).
struct TaskFilter {
  std::string state{}, source{};     // empty: any
  std::optional<Time> from{}, to{};  // a task without a window overlaps nothing once either is set
  bool windowless_by_added = false;  // ... unless this is set and it was added within [from, to)
  long limit = 100, offset = 0;
};
struct TaskPage {
  long total = 0;  // how many passed the filters, on every page
  std::vector<TaskRow> rows;
};
Result<TaskPage> find_tasks(const Store& store, const TaskFilter& filter);

// How many stored tasks are in each state.
Result<std::map<std::string, long>> count_tasks_by_state(const Store& store);

// How many stored tasks each robot holds in each state: robot -> state -> count ("" for the
// tasks allocated to no robot). One grouped query, cheap enough for every look at the robots.
Result<std::map<std::string, std::map<std::string, long>>> count_tasks_by_robot(const Store& store);

}  // namespace rondo::store
