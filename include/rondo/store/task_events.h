// The task event log: an append-only record of everything that happened to each task (every state
// change with its reason, and other notable moments). Rows are never updated or deleted: there is
// no API for it and the schema's triggers refuse it. The sequence number gives the order of appends.
//
//   Result<std::int64_t> seq = append_task_event(db, {.time = now, .task_id = "t1",
//                                                     .event = "door_closed", .reason = "A-110"});
//   Result<std::vector<TaskEvent>> all = read_task_events(db);          // every event, by seq
//   Result<std::vector<TaskEvent>> newer = read_task_events(db, *seq);  // only those after seq
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct TaskEvent {
  std::int64_t seq = 0;  // assigned by the store: increasing, never reused; ignored when appending
  Time time;
  std::string task_id;  // a task in the task table
  std::string event;    // a state name for state changes ("queued", "failed", ...) or another event
  std::string reason;   // why, for people; may be empty

  bool operator==(const TaskEvent&) const = default;
};

// Appends `event` in its own committed transaction and returns its sequence number.
// Errors: kNotFound (event.task_id is not a stored task), kStorage.
Result<std::int64_t> append_task_event(Store& store, const TaskEvent& event);

// The events with seq > after_seq, in append order. 0 reads the whole log.
Result<std::vector<TaskEvent>> read_task_events(const Store& store, std::int64_t after_seq = 0);
// The events of one task, in append order (empty for an unknown task).
Result<std::vector<TaskEvent>> read_task_events_of(const Store& store, std::string_view task_id);

}  // namespace rondo::store
