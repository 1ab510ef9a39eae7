// Reading a store back when the executive restarts (after a crash, a reboot, an upgrade): every
// stored task with the event that moved it to its state and whether its last schedule dropped it
// for now, the whole event log, where the stored record ends in time, the robot's last known state
// and the store's identity (meta).
//
//   Result<StoredRun> back = read_back(db, "robot");
//   for (const StoredTask& t : back->tasks) ...      // in the order they were accepted
//   Time resume_at = back->latest().value_or(start); // the latest time anything was stored at
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/events.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"

namespace rondo::store {

// The event names the read-back interprets (written by the executor's task book).
inline constexpr std::string_view kDroppedForNowEvent = "dropped for now";
inline constexpr std::string_view kReOfferedEvent = "re-offered";

struct StoredTask {
  TaskRow row;
  // The latest event of the task named after its current state: the change that put it there
  // (its code and reason are the task's outcome). Empty only for a store written without events.
  std::optional<Event> last_transition;
  // The latest "dropped for now" event, when nothing moved the task since (no later state change,
  // no later "re-offered"): the task waits to be offered to the scheduler again.
  std::optional<Event> dropped_for_now;
  int added_events = 0;  // events with code "added": one for a task stored once
  // When its latest run began: its first waiting, navigating or acting since it was last queued.
  std::optional<Time> started{};
};

struct StoredRun {
  std::vector<StoredTask> tasks;       // in the order they were accepted (insertion order)
  std::vector<Event> events;           // the whole event log, in append order
  LogEnd log_end;                      // the latest event's seq and time (0 and epoch when none)
  std::optional<Time> traversals_end;  // the latest end (start + duration) of a stored traversal
  std::optional<RobotState> robot;     // the robot's last known state, if ever saved
  std::map<std::string, std::string> meta;

  // The latest time anything was stored at: events, traversals, the robot's state; nothing for an
  // empty store.
  std::optional<Time> latest() const;
};

// Errors: kStorage (including a task whose stored JSON no longer parses).
Result<StoredRun> read_back(const Store& store, std::string_view robot);

// Stored tasks with their last transition and drop for now, read from each one's events (for a
// task the executor no longer holds: a finished one). Errors: kStorage.
Result<std::vector<StoredTask>> read_stored_tasks(const Store& store, std::vector<TaskRow> rows);
// One stored task; nothing when the store has no such task. Errors: kStorage.
Result<std::optional<StoredTask>> read_stored_task(const Store& store, std::string_view id);

}  // namespace rondo::store
