// The executor rebuilt from its store after a restart (a crash, a reboot, an upgrade): every task
// comes back in its state, a task that was running comes back interrupted and goes back to the
// queue, the drops for now are offered again, and the book's counts cover the whole run.
#include <fmt/format.h>

#include <utility>

#include "rondo/core/document.h"
#include "rondo/core/task_codec.h"
#include "rondo/exec/executor.h"
#include "deliveries.h"
#include "dispatcher.h"
#include "rondo/store/observations.h"
#include "rondo/store/read_back.h"

namespace rondo::exec {
namespace {

constexpr const char* kInterruptedReason = "interrupted: the executive restarted while it ran";

}  // namespace

Status Executor::restore() {
  if (started_ || !book_.order().empty())
    return Error::internal("Executor::restore() runs once, before start() and before any task is added");
  RONDO_ASSIGN_OR_RETURN(store::StoredRun run, store::read_back(store_, options_.robot_name));
  // Everything is decoded before anything is recorded: a store that cannot be read back leaves
  // the executor empty.
  std::vector<TaskRecord> records;
  records.reserve(run.tasks.size());
  for (const store::StoredTask& t : run.tasks) {
    RONDO_ASSIGN_OR_RETURN(TaskRecord r, record_of(t, zone_));
    records.push_back(std::move(r));
  }
  book_.restore_counts(run.events);
  for (TaskRecord& r : records) {
    deliveries_->add(r.task);  // what is on board follows from the restored states
    book_.restore(std::move(r));
  }
  RONDO_RETURN_IF_ERROR(building_.restore_learning());
  restore_battery();  // executor_battery.cpp

  const Time now = clock_.now();
  for (const TaskId& id : book_.order()) {
    TaskRecord& r = book_.at(id);
    if (is_final(r.state)) continue;
    // The deployment may have changed meanwhile (a node renamed): a task it can no longer run
    // ends with that reason instead of being run on a place that is gone.
    if (Status here = runs_here(r.task); !here) {
      book_.transition(id, TaskState::kFailed, Outcome::kNoLongerValid,
                       "no longer valid after the restart: " + here.error().message);
      continue;
    }
    const bool on_demand = r.task.kind == TaskKind::kOnDemand;
    if (r.state != TaskState::kQueued) {
      // It was waiting for, driving to or acting on this task when the executive stopped.
      if (r.actions_done >= r.action_count() && (r.task.end_node.empty() || r.task.end_node == r.task.start_node)) {
        // Its last action was stored as done, its success not yet: nothing is left to run.
        book_.transition(id, TaskState::kSucceeded, Outcome::kDone, "done: every action finished before the restart");
        continue;
      }
      if (on_demand || !r.task.window || now + r.remaining() <= r.task.window->deadline) {
        book_.transition(id, TaskState::kQueued, Outcome::kInterrupted,
                         fmt::format("{}; back in the queue", kInterruptedReason));
      } else {
        book_.transition(id, TaskState::kFailed, Outcome::kInterrupted,
                         fmt::format("{}; its window no longer allows it", kInterruptedReason));
        continue;
      }
    }
    if (on_demand) {
      dispatcher_->queue_on_demand(id);
      if (r.not_before && *r.not_before > now) clock_.schedule_at(*r.not_before, [this] { on_demand_due(); });
    } else if (r.door_wait && r.task.window) {
      // Blocked by a door seen closed: it waits for the door again, with its retry and its end.
      const DoorWait wait = *r.door_wait;
      wait_for_door(id, wait);
    } else if (r.dropped_for_now && r.task.window) {
      // Offered again at every reschedule, and dropped for good once its window cannot be met.
      dispatcher_->defer(id);
      clock_.schedule_at(r.task.window->deadline - r.remaining() + milliseconds(1),
                         [this] { (void)reoffer_deferred(); });
    }
    // A queued standard task: start() schedules it.
  }
  // The models learnt so far, at once rather than at the next nightly refit.
  if (run.traversals_end) refit();
  return Status{};
}

}  // namespace rondo::exec
