#include <fmt/format.h>

#include <algorithm>

#include "steps.h"
#include "text.h"

namespace rondo::exec {

ActStep::ActStep(StepContext& ctx, StepHooks hooks, TaskId task, const Arrival& arrival)
    : RobotStep(ctx, std::move(hooks)), task_(std::move(task)), arrival_(arrival) {}

void ActStep::start() {
  const Time now = ctx_.clock.now();
  const TaskRecord& r = ctx_.book.at(task_);
  since_ = now;
  expected_ = r.remaining();
  index_ = r.actions_done;  // a task that was preempted goes on after the actions it did
  ctx_.book.transition(task_, TaskState::kActing, Outcome::kArrived,
                       fmt::format("arrived at {} after {} (expected {}); expected processing {}",
                                   ctx_.map.node(arrival_.target()).name, duration_text(now - arrival_.started()),
                                   duration_text(arrival_.expected()), duration_text(r.remaining())));
  monitor_.arm(limit(r), [this](const std::string& why) { hooks_.overrun(Outcome::kActionOverrun, why); });
  if (ctx_.in_fault) monitor_.suspend();
  run_next();
}

// The overrun factor times the processing time still to spend, plus the slack; or, when the
// people this task waits for are known to take longer than that at times, the share of its
// patience still to spend (TaskRecord::patience) plus the slack.
Monitor::Limit ActStep::limit(const TaskRecord& r) const {
  const ExecutorOptions& o = ctx_.options;
  Monitor::Limit l =
      Monitor::limit("action overrun: still acting", "the processing time", r.remaining(), o.action_overrun, o.action_slack);
  if (!r.patience) return l;
  const Duration left = r.share_left(*r.patience);
  if (left + o.action_slack <= l.after) return l;
  l.after = left + o.action_slack;
  l.reason = fmt::format("action overrun: still acting after {}, the limit is the {:.0f}th percentile of the learned "
                         "times {} + {}",
                         duration_text(l.after), o.person_patience * 100, duration_text(left),
                         duration_text(o.action_slack));
  return l;
}

void ActStep::run_next() {
  if (hooks_.stop_here()) return end({.status = StepEnd::Status::kHalted});  // between two actions
  const TaskRecord& r = ctx_.book.at(task_);
  const Task& task = r.task;
  const std::size_t n = r.action_count();
  if (index_ >= n) {
    monitor_.cancel();
    return end({.status = StepEnd::Status::kDone,
                .outcome = Outcome::kDone,
                .reason = fmt::format("done: {} of actions (expected {})", duration_text(ctx_.clock.now() - since_),
                                      duration_text(expected_))});
  }
  if (ctx_.in_fault) return;  // resume() runs it
  // A task without actions is its processing time spent at the place: one action named after it.
  const Action action = task.actions.empty() ? Action{.name = task.activity.empty() ? "task" : task.activity, .args = {}}
                                             : task.actions[index_];
  running_ = action.name;
  ctx_.before_command();
  ctx_.robot.run_action(action, r.expected_duration() / static_cast<std::int64_t>(n));
}

void ActStep::on_action_finished(const ActionResult& r) {
  running_.reset();
  if (r.outcome == ActionOutcome::kCancelled || halting()) return end({.status = StepEnd::Status::kHalted});
  if (r.outcome == ActionOutcome::kRobotFault) {
    // Not the action's fault: it runs again once the robot is ready.
    ctx_.book.note(task_, EventKind::kInterrupted, Outcome::kRobotFault,
                   fmt::format("action {} stopped by a robot fault{}{}; it runs again when the robot is ready", r.name,
                               r.message.empty() ? "" : ": ", r.message));
    if (!ctx_.in_fault) run_next();
    return;
  }
  if (r.outcome == ActionOutcome::kFailed) {
    return end({.status = StepEnd::Status::kFailed,
                .outcome = Outcome::kActionFailed,
                .reason = fmt::format("action {} failed{}{}", r.name, r.message.empty() ? "" : ": ", r.message)});
  }
  ctx_.book.set_progress(task_, ++index_);
  run_next();
}

}  // namespace rondo::exec
