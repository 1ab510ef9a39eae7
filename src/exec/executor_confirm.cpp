// A load or unload confirmed by a person through the API (POST /api/v1/tasks/{id}/confirm): the
// robot's action is ended with Robot::cancel(), and the cancel it reports counts as the action
// done, as if the person had confirmed at the robot.
#include <fmt/format.h>

#include "loading_times.h"
#include "rondo/exec/executor.h"
#include "task_run.h"

namespace rondo::exec {

Status Executor::confirm_action(const TaskId& id, const std::string& by) {
  const std::optional<TaskState> state = book_.state_of(id);
  if (!state) return Error::not_found(fmt::format("no task '{}'", id));
  const std::optional<std::string> action = run_ && run_->id() == id ? run_->running_action() : std::nullopt;
  if (!action || !loading_.learns(*action))
    return Error{ErrorCode::kConflict,
                 fmt::format("task {} is {}, not loading or unloading: nothing to confirm", id, to_string(*state))};
  if (confirmed_ == id)
    return Error{ErrorCode::kConflict, fmt::format("task {}: the {} is already confirmed", id, *action)};
  confirmed_ = id;
  book_.note(id, EventKind::kConfirmed, Outcome::kConfirmed,
             fmt::format("{} confirmed{}", *action, by.empty() ? std::string() : " by " + by));
  robot_.cancel();
  return Status{};
}

ActionResult Executor::confirmed_result(const ActionResult& reported) {
  if (!confirmed_) return reported;
  const bool ours = run_ && run_->id() == *confirmed_;
  confirmed_.reset();
  if (!ours || reported.outcome != ActionOutcome::kCancelled || run_->stopping()) return reported;
  ActionResult done = reported;
  done.outcome = ActionOutcome::kSucceeded;
  done.message.clear();
  return done;
}

}  // namespace rondo::exec
