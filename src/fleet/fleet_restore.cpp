// The fleet rebuilt from its store after a restart (a crash, a reboot, an upgrade): every task comes
// back in its state and on its robot, a task that was running comes back interrupted and goes back
// to its robot's queue, the drops for now are offered again, and the book's counts cover the whole
// run. A task of a robot the deployment no longer has is allocated again.
#include <fmt/format.h>

#include <utility>

#include "rondo/fleet/fleet.h"
#include "rondo/store/read_back.h"

namespace rondo::fleet {
namespace {

constexpr const char* kInterruptedReason = "interrupted: the executive restarted while it ran";

}  // namespace

Status Fleet::restore() {
  exec::TaskBook& book = building_.book;
  if (started_ || !book.order().empty() || robots_.empty())
    return Error::internal("Fleet::restore() runs once, with its robots, before start() and before any task is added");
  RONDO_ASSIGN_OR_RETURN(store::StoredRun run, store::read_back(building_.store, robot().name()));
  // Everything is decoded before anything is recorded: a store that cannot be read back leaves
  // the fleet empty.
  std::vector<exec::TaskRecord> records;
  records.reserve(run.tasks.size());
  for (const store::StoredTask& t : run.tasks) {
    RONDO_ASSIGN_OR_RETURN(exec::TaskRecord r, exec::record_of(t, building_.zone));
    records.push_back(std::move(r));
  }
  book.restore_counts(run.events);
  for (exec::TaskRecord& r : records) book.restore(std::move(r));
  // Unfinished tasks of a robot that is gone go to the robots there are now.
  for (const TaskId& id : book.order()) {
    const exec::TaskRecord& r = book.at(id);
    if (is_final(r.state) || index_of(r.robot) < robots_.size()) continue;
    if (runs_here(r.task) && !cannot_run(r.task)) {
      if (auto moved = book.allocate(id, robots_[allocate({r.task}).front().robot]->name()); !moved)
        book.write_error(moved.error().message);
    }
  }
  // What each robot knew of its tasks (what is on board follows from the restored states); a
  // fleet of one knows every task, whoever it was stored for.
  for (const TaskId& id : book.order()) {
    exec::Executor* robot = find_robot(book.at(id).robot);
    if (!robot && robots_.size() == 1) robot = robots_.front().get();
    if (robot) robot->restored(book.at(id));
  }
  RONDO_RETURN_IF_ERROR(building_.restore_learning());
  for (const auto& r : robots_) r->restore_battery();

  const Time now = building_.clock.now();
  for (const TaskId& id : book.order()) {
    exec::TaskRecord& r = book.at(id);
    if (is_final(r.state)) continue;
    // The deployment may have changed meanwhile (a node renamed, a robot gone): a task it can no
    // longer run ends with that reason instead of being run on a place that is gone.
    Status here = runs_here(r.task);
    if (here && index_of(r.robot) == robots_.size())
      here = Error::invalid(fmt::format("task {}: no robot of this deployment can run it", id));
    if (!here) {
      book.transition(id, TaskState::kFailed, exec::Outcome::kNoLongerValid,
                      "no longer valid after the restart: " + here.error().message);
      continue;
    }
    const bool on_demand = r.task.kind == TaskKind::kOnDemand;
    if (r.state != TaskState::kQueued) {
      // Its robot was waiting for, driving to or acting on this task when the executive stopped.
      if (r.actions_done >= r.action_count() && (r.task.end_node.empty() || r.task.end_node == r.task.start_node)) {
        // Its last action was stored as done, its success not yet: nothing is left to run.
        book.transition(id, TaskState::kSucceeded, exec::Outcome::kDone,
                        "done: every action finished before the restart");
        continue;
      }
      if (on_demand || !r.task.window || now + r.remaining() <= r.task.window->deadline) {
        book.transition(id, TaskState::kQueued, exec::Outcome::kInterrupted,
                        fmt::format("{}; back in the queue", kInterruptedReason));
      } else {
        book.transition(id, TaskState::kFailed, exec::Outcome::kInterrupted,
                        fmt::format("{}; its window no longer allows it", kInterruptedReason));
        continue;
      }
    }
    robots_[index_of(r.robot)]->restore_task(id);
  }
  // The models learnt so far, at once rather than at the next nightly refit.
  if (run.traversals_end) refit();
  return Status{};
}

}  // namespace rondo::fleet
