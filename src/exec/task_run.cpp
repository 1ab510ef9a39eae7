#include "task_run.h"

#include <fmt/format.h>

#include "spec_tasks.h"

namespace rondo::exec {

TaskRun::TaskRun(StepContext& ctx, TaskId id, std::optional<EarlyWait> wait, std::function<void(End)> ended)
    : ctx_(ctx), id_(std::move(id)), ended_(std::move(ended)) {
  const Task& t = task();
  const map::NodeIndex here = ctx_.robot.location();
  map::NodeIndex place = t.start_node.empty() ? here : *ctx_.map.find_node(t.start_node);
  if (wait) {
    auto w = std::make_unique<WaitStep>(ctx_, hooks(), id_, std::move(*wait));
    wait_ = w.get();
    steps_.push_back(std::move(w));
  }
  // A spec task follows its formula's policy until it is satisfied, and acts there; once it was
  // (a re-run after a preemption while acting), it goes back to where it was.
  const std::optional<map::NodeIndex> satisfied_at = spec_place(ctx_.map, ctx_.book.at(id_));
  if (t.has_spec() && !satisfied_at) {
    auto journey = std::make_unique<SpecStep>(ctx_, hooks(), id_);
    auto act = std::make_unique<ActStep>(ctx_, hooks(), id_, *journey);
    act_ = act.get();
    steps_.push_back(std::move(journey));
    steps_.push_back(std::move(act));
    return;
  }
  if (satisfied_at) place = *satisfied_at;
  auto to_place = std::make_unique<NavigateStep>(ctx_, hooks(), NavigateStep::Purpose::kToStart, id_, place);
  auto act = std::make_unique<ActStep>(ctx_, hooks(), id_, *to_place);
  act_ = act.get();
  steps_.push_back(std::move(to_place));
  steps_.push_back(std::move(act));
  // A task that ends elsewhere than where its actions leave the robot is driven there.
  if (!t.end_node.empty() && t.end_node != t.start_node)
    steps_.push_back(std::make_unique<NavigateStep>(ctx_, hooks(), NavigateStep::Purpose::kToEnd, id_,
                                                    *ctx_.map.find_node(t.end_node)));
}

StepHooks TaskRun::hooks() {
  return {.ended = [this](StepEnd e) { step_ended(std::move(e)); },
          .overrun = [this](Outcome o, const std::string& why) { overrun(o, why); },
          .stop_here = [this] { return stop_here(); }};
}

void TaskRun::start() {
  TaskRecord& r = ctx_.book.at(id_);
  run_since_ = ctx_.clock.now();
  if (!r.started) r.started = run_since_;
  index_ = 0;
  steps_.front()->start();
}

std::optional<Time> TaskRun::acting_since() const {
  if (current() == act_) return act_->since();
  return std::nullopt;
}

std::optional<std::string> TaskRun::running_action() const {
  if (current() == act_) return act_->running_action();
  return std::nullopt;
}

std::optional<Time> TaskRun::acting_until() const {
  if (current() == act_) return act_->expected_end();
  return std::nullopt;
}

void TaskRun::next_step() {
  overrun_held_.reset();  // a monitor held back for the step that ended is moot now
  ++index_;
  if (Step* s = current()) return s->start();
  finish({.requeue = false, .state = TaskState::kSucceeded, .outcome = done_.outcome, .reason = done_.reason});
}

void TaskRun::step_ended(StepEnd e) {
  switch (e.status) {
    case StepEnd::Status::kDone:
      if (current() == act_) done_ = e;
      return next_step();
    case StepEnd::Status::kFailed:
      return finish({.requeue = false, .state = TaskState::kFailed, .outcome = e.outcome, .reason = e.reason});
    case StepEnd::Status::kBlocked:  // the executor decides whether it waits (Executor::hold_back)
      return finish(
          {.requeue = true, .state = TaskState::kQueued, .outcome = e.outcome, .reason = e.reason, .edge = e.edge,
           .not_before = e.not_before});
    case StepEnd::Status::kHalted:
      break;
  }
  switch (stop_) {
    case Stop::kOverrun:
      return finish({.requeue = false, .state = TaskState::kFailed, .outcome = stop_outcome_, .reason = stop_reason_});
    case Stop::kCancel:
      return finish({.requeue = false, .state = TaskState::kCancelled, .outcome = stop_outcome_, .reason = stop_reason_});
    case Stop::kPreempt:
      return finish({.requeue = true, .state = TaskState::kQueued, .outcome = stop_outcome_, .reason = stop_reason_});
    case Stop::kNone:  // the robot stopped by itself
      return finish({.requeue = false, .state = TaskState::kFailed, .outcome = Outcome::kActionFailed,
                     .reason = "stopped by the robot"});
  }
}

void TaskRun::stop(Stop why, Outcome outcome, std::string reason) {
  if (finished_) return;
  if (stop_ == Stop::kCancel || (stop_ != Stop::kNone && why != Stop::kCancel)) return;
  const bool under_way = stop_ != Stop::kNone;
  stop_ = why;
  stop_outcome_ = outcome;
  stop_reason_ = std::move(reason);
  if (Step* s = current(); s && !under_way) s->halt();
}

bool TaskRun::stop_here() {
  if (!cancel_pending_) return false;
  stop_ = Stop::kCancel;
  stop_outcome_ = Outcome::kCancelled;
  stop_reason_ = *std::exchange(cancel_pending_, std::nullopt);
  return true;
}

void TaskRun::overrun(Outcome outcome, const std::string& reason) {
  // A monitor of a run that has ended (retired, freed at the next robot callback) is moot; its
  // task may have left the book already (forget_finished).
  if (finished_) return;
  if (!interruptible()) {
    if (!overrun_held_)
      ctx_.book.note(id_, EventKind::kOverrun, Outcome::kOverrunHeld,
                     reason + "; the task is not interruptible now, so it goes on");
    overrun_held_ = std::make_pair(outcome, reason);
    return;
  }
  stop(Stop::kOverrun, outcome, reason);
}

bool TaskRun::set_robot_interruptible(bool interruptible) {
  robot_interruptible_ = interruptible;
  if (!interruptible || finished_ || !this->interruptible()) return false;
  if (cancel_pending_) {
    stop(Stop::kCancel, Outcome::kCancelled, *std::exchange(cancel_pending_, std::nullopt));
    return true;
  }
  if (overrun_held_) {
    const auto [outcome, reason] = *std::exchange(overrun_held_, std::nullopt);
    overrun(outcome, reason);
    return true;
  }
  return false;
}

void TaskRun::abandon_wait() {
  wait_->abandon();
  finished_ = true;
}

void TaskRun::finish(End end) {
  if (finished_) return;
  finished_ = true;
  ended_(std::move(end));
}

}  // namespace rondo::exec
