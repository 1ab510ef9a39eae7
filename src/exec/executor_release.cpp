// Handing tasks back to the fleet (Executor::release): re-allocation when a robot cannot work.
#include <fmt/format.h>

#include <set>

#include "deliveries.h"
#include "dispatcher.h"
#include "rondo/exec/executor.h"
#include "task_run.h"

namespace rondo::exec {

std::vector<TaskId> Executor::release() {
  std::vector<TaskId> queued(dispatcher_->planned().begin(), dispatcher_->planned().end());
  queued.insert(queued.end(), dispatcher_->on_demand().begin(), dispatcher_->on_demand().end());
  queued.insert(queued.end(), dispatcher_->deferred().begin(), dispatcher_->deferred().end());
  return release(queued);
}

const std::vector<TaskId>& Executor::deferred() const {
  return dispatcher_->deferred();
}

bool Executor::hand_back_running(std::function<void(const TaskId&)> handed) {
  if (!run_ || run_->waiting() || run_->stopping() || handing_back_) return false;
  const TaskId id = run_->id();
  const TaskRecord& r = book_.at(id);
  if (r.task.has_spec() || r.robot != name() || r.task.robot == name()) return false;
  if (r.task.delivery) return false;  // its pickup runs, or its item is on board: the job stays here
  handing_back_ = std::move(handed);
  run_->stop(TaskRun::Stop::kPreempt, Outcome::kRobotFault,
             fmt::format("{} cannot work: handed back to the fleet", name()));
  return true;
}

std::vector<TaskId> Executor::release(const std::vector<TaskId>& queued) {
  // A delivery job stays whole with the robot that began it.
  std::set<std::string> begun;
  for (const std::string& job : deliveries_->open()) {
    const Deliveries::Job* j = deliveries_->job(job);
    const bool pickup_runs = j && j->pickup && run_ && run_->id() == *j->pickup;
    if (pickup_runs || deliveries_->is_on_board(book_, job)) begun.insert(job);
  }
  std::vector<TaskId> released;
  for (const TaskId& id : queued) {
    const TaskRecord* r = book_.find(id);
    if (!r || is_final(r->state) || r->robot != name() || r->task.robot == name()) continue;
    if (run_ && run_->id() == id) continue;  // started
    if (r->task.delivery && begun.contains(r->task.delivery->job)) continue;
    released.push_back(id);
  }
  for (const TaskId& id : released) {
    dispatcher_->forget(id);
    book_.at(id).dropped_for_now.reset();  // its next robot drops it afresh, or plans it
    if (const auto& d = book_.at(id).task.delivery) deliveries_->hand_over(d->job);
  }
  return released;
}

}  // namespace rondo::exec
