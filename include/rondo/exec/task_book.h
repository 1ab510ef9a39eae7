// The task book: every task the executor knows, and the one place that changes a task's state.
// Each transition and each other event is written to the store (the task's row and the event log,
// with its outcome code and reason) before the executor goes on; a failed write is kept for the
// report and the run goes on (the store is the record, not the control). The book also counts the
// events that are not final outcomes (preemptions, drops for now, re-offers, faults), for the
// report.
//
//   TaskBook book(store, clock);
//   Result<std::vector<TaskId>> ids = book.add(tasks, "api");        // stored all or nothing
//   book.transition("t1", TaskState::kFailed, Outcome::kTooLate, "too late: ...");
//   book.note("t1", EventKind::kScheduled, Outcome::kScheduled, "planned start 09:10 (new tasks)");
//   book.note_robot(EventKind::kFault, Outcome::kRobotFault, "lost connection");
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/event_kind.h"
#include "rondo/exec/outcome.h"
#include "rondo/store/events.h"
#include "rondo/store/read_back.h"
#include "rondo/store/requests.h"
#include "rondo/store/store.h"

namespace rondo::exec {

// A door a task waits for (seen closed: the task waits as an opportunity), kept in the task's
// stored progress so that a restart brings the task back waiting for it.
struct DoorWait {
  std::string door;
  Time since{};         // when it was seen closed
  std::string seen_at;  // the node the robot saw it from
  bool operator==(const DoorWait&) const = default;
};

// What the executor knows of one task.
struct TaskRecord {
  Task task;
  std::string robot;  // the robot it is allocated to (fleet::Fleet); empty: none yet
  TaskState state = TaskState::kQueued;
  Outcome outcome = Outcome::kAdded;  // the code of the last transition
  std::string reason;                 // of the last transition
  std::string source;                 // who added it: "routine", "request", "api", ...
  Time added{};
  std::optional<Time> planned_start{}, planned_end{};  // from the latest schedule
  // A way it needs was found blocked: not scheduled to start before this (ExecutorOptions::blocked_edge).
  std::optional<Time> not_before{};
  std::optional<Time> started{}, ended{};  // left for it .. final state
  // Dropped by the last schedule but not given up: offered again at every reschedule while its
  // window can still be met (the outcome and reason of that drop are kept for the final one).
  std::optional<std::pair<Outcome, std::string>> dropped_for_now{};
  // Progress, kept when the task is preempted or interrupted: a re-run starts after the actions
  // already done (stored as the task's progress, {"actions_done": n}).
  std::size_t actions_done = 0;
  // Blocked by a door seen closed (stored with the progress, {"blocked": {door, since, seen_at}}).
  std::optional<DoorWait> door_wait{};
  // A spec task's automaton state after the nodes its journey has reached (none: not begun), kept
  // when it is preempted or interrupted so that what it has done stays done (stored with the
  // progress, {"spec_state": q}).
  std::optional<std::uint32_t> spec_state{};
  std::string spec_place{};  // where its formula was satisfied, and its actions run (empty: not yet)
  // The journey that satisfied it: the time its plan expected when it left, and the time it took
  // (for the report; not stored).
  std::optional<std::pair<Duration, Duration>> spec_journey{};
  // The processing time learned from experience (loading and unloading times), when the executor
  // knows better than the task's declared duration.
  std::optional<Duration> learned_duration{};
  // How long its actions may take before the action monitor stops them, when the people it waits
  // for are known to take longer than the overrun factor allows (ExecutorOptions::person_patience):
  // the learned quantile of each person's time, the other actions' shares as they are.
  std::optional<Duration> patience{};

  std::size_t action_count() const { return std::max<std::size_t>(1, task.actions.size()); }
  // When it may start: its window's release, or later while a way it needs is held to be blocked
  // (never after the deadline). Precondition: the task has a window.
  Time release() const {
    return std::min(std::max(task.window->release, not_before.value_or(task.window->release)), task.window->deadline);
  }
  // The latest it may leave and still be done in time: its deadline less the processing time still
  // to spend; an on-demand task (no window) may wait `on_demand_patience` after it was added.
  Time latest_start(Duration on_demand_patience) const {
    return task.window ? task.window->deadline - remaining() : added + on_demand_patience;
  }
  Duration expected_duration() const { return learned_duration.value_or(task.duration); }
  // The processing time still to spend: the share of the actions not done yet.
  Duration remaining() const { return share_left(expected_duration()); }
  // The share of `whole` (a time for all its actions) that falls to the actions not done yet.
  Duration share_left(Duration whole) const {
    const std::size_t n = action_count();
    return whole * static_cast<std::int64_t>(n - std::min(actions_done, n)) / static_cast<std::int64_t>(n);
  }
};

class TaskBook {
 public:
  // Precondition: store and clock outlive the book.
  TaskBook(store::Store& store, const Clock& clock) : store_(store), clock_(clock) {}

  // Stores the tasks, all or nothing, then records them as queued, each allocated to its robot in
  // `robots` (the same order; empty: every task to none). kInvalidInput for an empty or repeated id
  // or one already in the book or the store (which also holds the finished tasks that have left the
  // book); kStorage when the store cannot write. With `taken`, the queued request they come from is
  // marked taken in the same transaction.
  Status add(std::vector<Task> tasks, std::string_view source, const store::RequestTaken* taken = nullptr,
             const std::vector<std::string>& robots = {});
  // Allocates a task to another robot (stored); precondition: the task is in the book.
  Status allocate(const TaskId& id, const std::string& robot);

  // Restore after a restart (exec/executor_restore.cpp): records a task read back from the store
  // as it is, without writing anything (precondition: its id is not in the book yet), and counts
  // the stored events as the book counted them when they were written, so that the report covers
  // the whole run.
  void restore(TaskRecord record);
  void restore_counts(const std::vector<store::Event>& events);

  // With forget_finished (rondo serve), a task that reaches a final state leaves the book: the
  // first one since the last sweep() calls `schedule_sweep` (the executor posts a sweep() on its
  // clock, so whatever runs now still finds the record), and sweep() erases them. They stay in the
  // store: state_of(), known() and lookup() read it. Without it (rondo run, whose report covers
  // every task) finished tasks stay.
  void forget_finished(std::function<void()> schedule_sweep) { schedule_sweep_ = std::move(schedule_sweep); }
  // Erases the finished tasks from memory; returns their ids.
  std::vector<TaskId> sweep();

  // In memory: every task not final, and the finished ones not swept (or all, without forgetting).
  bool contains(const TaskId& id) const { return records_.contains(id); }
  const TaskRecord* find(const TaskId& id) const {
    const auto it = records_.find(id);
    return it == records_.end() ? nullptr : &it->second;
  }
  // Whether a task the executor was given is over: in a final state, or gone from memory.
  bool finished(const TaskId& id) const {
    const TaskRecord* r = find(id);
    return r == nullptr || is_final(r->state);
  }
  // A task's state from memory, else from the store; nothing for a task the store has not either.
  std::optional<TaskState> state_of(const TaskId& id) const;
  // In memory or in the store.
  bool known(const TaskId& id) const { return contains(id) || state_of(id).has_value(); }
  // A copy of the task's record from memory, else rebuilt from the store (task, state, outcome and
  // reason, source, added, ended); nothing for an unknown task. Errors: kStorage.
  Result<std::optional<TaskRecord>> lookup(const TaskId& id, const TimeZone& zone) const;
  const TaskRecord& at(const TaskId& id) const { return records_.at(id); }
  TaskRecord& at(const TaskId& id) { return records_.at(id); }
  const std::map<TaskId, TaskRecord>& records() const { return records_; }
  const std::vector<TaskId>& order() const { return order_; }  // in the order added

  // Moves the task to `state`, stores the change and its event.
  void transition(const TaskId& id, TaskState state, Outcome outcome, const std::string& reason);
  // Records and stores how many of the task's actions are done.
  void set_progress(const TaskId& id, std::size_t actions_done);
  // Records and stores a spec task's automaton state (TaskRecord::spec_state).
  void set_spec_state(const TaskId& id, std::uint32_t state, const std::string& place = {});
  // Records and stores the door the task waits for (none: it waits for nothing).
  void set_door_wait(const TaskId& id, std::optional<DoorWait> wait);
  // Held back for a way found blocked (TaskRecord::not_before), stored with its progress so that a
  // restart keeps it. Precondition: the task is in the book.
  void set_not_before(const TaskId& id, Time t);
  // A task's progress as stored ({"actions_done": n, "blocked": {...}}), and read back into `r`
  // (restore; what it does not understand is left as it was).
  static Json progress_json(const TaskRecord& r);
  static void read_progress(const Json& progress, TaskRecord& r);
  // An event of a task that is not a change of its state.
  void note(const TaskId& id, EventKind event, Outcome outcome, const std::string& reason);
  // Events about a robot (by its name), a request (`about`: its id) or the schedule.
  void note_robot(const std::string& robot, EventKind event, Outcome outcome, const std::string& reason);
  void note_schedule(EventKind event, Outcome outcome, const std::string& reason);
  // With `taken`, the queued request is marked taken in the event's transaction.
  void note_request(const std::string& about, EventKind event, Outcome outcome, const std::string& reason,
                    const store::RequestTaken* taken = nullptr);
  // The request's event and its mark (with its meta entries) in one transaction; the store's error,
  // with nothing written, when it cannot be taken (kConflict: taken already).
  Status take_request(const store::RequestTaken& taken, EventKind event, Outcome outcome,
                      const std::string& reason);

  // How many events were written that are not final states, by event name and code (for the
  // report): {"preempted": {kPreemptedOnDemand: 3}, "dropped for now": {...}, "fault": {...}}.
  const std::map<std::string, std::map<Outcome, int>>& event_counts() const { return event_counts_; }
  // Store writes that failed (the run goes on; the caller reports them).
  const std::vector<std::string>& write_errors() const { return write_errors_; }
  void write_error(std::string message) { write_errors_.push_back(std::move(message)); }
  store::Store& store() { return store_; }

 private:
  void append(store::Event event, const store::RequestTaken* taken = nullptr);
  void finished_now(const TaskId& id);

  store::Store& store_;
  const Clock& clock_;
  std::map<TaskId, TaskRecord> records_;
  std::vector<TaskId> order_;
  std::map<std::string, std::map<Outcome, int>> event_counts_;
  std::vector<std::string> write_errors_;
  std::function<void()> schedule_sweep_;
  std::vector<TaskId> finished_;  // final since the last sweep (only with forget_finished)
};

// The record of a stored task, as the book knew it when it was stored (restore and lookup()).
// Errors: kStorage (stored JSON that no longer decodes).
Result<TaskRecord> record_of(const store::StoredTask& stored, const TimeZone& zone);

}  // namespace rondo::exec
