// The executor running tasks: what to do next, waiting, running actions, the two monitors and
// preemption (navigation is in executor_navigation.cpp).
#include <fmt/format.h>

#include <algorithm>
#include <tuple>
#include <utility>

#include "rondo/exec/executor.h"

namespace rondo::exec {
namespace {

std::string minutes_text(Duration d) { return format_duration(std::chrono::round<std::chrono::seconds>(d)); }

}  // namespace

void Executor::kick() {
  switch (phase_) {
    case Phase::kIdle:
      if (wait_timer_ != 0) clock_.cancel(wait_timer_);
      wait_timer_ = 0;
      next();
      return;
    case Phase::kDocking:
      if (!robot_.busy()) {
        phase_ = Phase::kIdle;
        next();
        return;
      }
      cancel_intent_ = CancelIntent::kLeaveDockTrip;
      robot_.cancel();
      return;
    case Phase::kWaiting: {
      clock_.cancel(wait_timer_);
      wait_timer_ = 0;
      stats_.waiting += clock_.now() - wait_start_;
      const TaskId id = *current_;
      current_.reset();
      phase_ = Phase::kIdle;
      book_.transition(id, TaskState::kQueued, Outcome::kScheduleChanged, "waiting interrupted: the schedule changed");
      if (std::find(schedule_.begin(), schedule_.end(), id) == schedule_.end()) schedule_.insert(schedule_.begin(), id);
      next();
      return;
    }
    case Phase::kNavigating:
    case Phase::kActing:
      return;
  }
}

void Executor::next() {
  if (phase_ != Phase::kIdle || robot_.busy() || fault_) return;  // a fault: on_ready() comes back here
  if (wait_timer_ != 0) clock_.cancel(wait_timer_);
  wait_timer_ = 0;
  const Time now = clock_.now();
  const map::NodeIndex here = robot_.location();
  if (!on_demand_.empty()) {
    const TaskId id = on_demand_.front();
    on_demand_.pop_front();
    start_task(id);
    return;
  }
  while (!schedule_.empty()) {
    const TaskId id = schedule_.front();
    const Task& task = book_.at(id).task;
    const map::NodeIndex start = *map_.find_node(task.start_node);
    const Duration travel = travel_->travel(here, start, now);
    const Time latest_start = task.window->deadline - task.duration;
    if (travel >= kUnreachable || now + travel > latest_start) {
      schedule_.erase(schedule_.begin());
      const std::string reason =
          travel >= kUnreachable
              ? fmt::format("too late: {} cannot be reached from {} at {}", task.start_node, map_.node(here).name,
                            fmt_time(now))
              : fmt::format("too late: leaving {} at {} arrives at {} about {} (travel {}), after the latest start "
                            "{} that finishes by {}",
                            map_.node(here).name, fmt_time(now), task.start_node, fmt_time(now + travel),
                            minutes_text(travel), fmt_time(latest_start), fmt_time(task.window->deadline));
      book_.transition(id, TaskState::kFailed, travel >= kUnreachable ? Outcome::kNoRoute : Outcome::kTooLate, reason);
      reschedule({}, "task " + id + " failed");
      continue;
    }
    const Time depart = task.window->release - travel;
    if (now < depart) {
      const Duration wait = depart - now;
      if (wait > options_.dock_when_waiting_over) {
        if (here != options_.dock) {
          go_to_dock();
          return;
        }
        wait_timer_ = clock_.schedule_at(depart, [this] {
          wait_timer_ = 0;
          next();
        });
        return;
      }
      schedule_.erase(schedule_.begin());
      current_ = id;
      phase_ = Phase::kWaiting;
      wait_start_ = now;
      TaskRecord& r = book_.at(id);
      if (!r.started) r.started = now;
      book_.transition(id, TaskState::kWaiting, Outcome::kEarly,
                 fmt::format("early: waits {} at {} so as to arrive at {} when the window opens at {}",
                             minutes_text(wait), map_.node(here).name, task.start_node,
                             fmt_time(task.window->release)));
      wait_timer_ = clock_.schedule_at(depart, [this, id] {
        wait_timer_ = 0;
        stats_.waiting += clock_.now() - wait_start_;
        phase_ = Phase::kIdle;
        current_.reset();
        start_task(id);
      });
      return;
    }
    schedule_.erase(schedule_.begin());
    start_task(id);
    return;
  }
  if (here != options_.dock) go_to_dock();
}

void Executor::start_task(const TaskId& id) {
  TaskRecord& r = book_.at(id);
  const Task& task = r.task;
  const Time now = clock_.now();
  current_ = id;
  failed_edges_ = 0;
  robot_interruptible_ = true;
  if (!r.started) r.started = now;
  const map::NodeIndex here = robot_.location();
  const map::NodeIndex target = task.start_node.empty() ? here : *map_.find_node(task.start_node);
  const Duration expected = travel_->travel(here, target, now);
  if (task.kind == TaskKind::kOnDemand) {
    // The rest of the day is planned around it: it runs now.
    phase_ = Phase::kNavigating;
    acting_start_ = now;
    reschedule({}, "on-demand task " + id + " runs now");
  }
  if (expected >= kUnreachable) {
    phase_ = Phase::kNavigating;
    finish_task(TaskState::kFailed, Outcome::kNoRoute,
                fmt::format("no route: from {} to {} at {}", map_.node(here).name, task.start_node, fmt_time(now)));
    return;
  }
  book_.transition(id, TaskState::kNavigating, Outcome::kDeparted,
             fmt::format("to {} from {}, expected travel {}", map_.node(target).name, map_.node(here).name,
                         minutes_text(expected)));
  begin_navigation(target, expected);
}

void Executor::start_actions() {
  const TaskId& id = *current_;
  const Task& task = book_.at(id).task;
  const Time now = clock_.now();
  phase_ = Phase::kActing;
  acting_start_ = now;
  action_index_ = 0;
  book_.transition(id, TaskState::kActing, Outcome::kArrived,
             fmt::format("arrived at {} after {} (expected {}); expected processing {}", map_.node(nav_target_).name,
                         minutes_text(now - nav_start_), minutes_text(nav_expected_), minutes_text(task.duration)));
  action_monitor_ = arm_monitor(CancelIntent::kActionOverrun, "action overrun: still acting", "the processing time",
                                task.duration, options_.action_overrun, options_.action_slack);
  run_next_action();
}

void Executor::run_next_action() {
  if (cancel_pending_) {  // between two actions the task can be stopped: the moment a cancel waited for
    finish_task(TaskState::kCancelled, Outcome::kCancelled, *cancel_pending_);
    return;
  }
  const Task& task = book_.at(*current_).task;
  const std::size_t n = std::max<std::size_t>(1, task.actions.size());
  if (action_index_ >= n) {
    finish_task(TaskState::kSucceeded, Outcome::kDone, fmt::format("done: {} of actions (expected {})",
                                                   minutes_text(clock_.now() - acting_start_),
                                                   minutes_text(task.duration)));
    return;
  }
  // A task without actions is its processing time spent at the place: one action named after it.
  const Action action = task.actions.empty() ? Action{.name = task.activity.empty() ? "task" : task.activity, .args = {}}
                                             : task.actions[action_index_];
  robot_.run_action(action, task.duration / static_cast<std::int64_t>(n));
}

void Executor::on_action_finished(const ActionResult& result) {
  stats_.acting += result.duration;
  if (result.outcome == ActionOutcome::kCancelled) {
    handle_cancelled();
    return;
  }
  if (phase_ != Phase::kActing || !current_) return;
  if (result.outcome == ActionOutcome::kRobotFault) {
    // Not the action's fault: it runs again once the robot is ready.
    book_.note(*current_, "interrupted", Outcome::kRobotFault,
         fmt::format("action {} stopped by a robot fault{}{}; it runs again when the robot is ready", result.name,
                     result.message.empty() ? "" : ": ", result.message));
    if (!fault_) run_next_action();
    return;
  }
  if (result.outcome == ActionOutcome::kFailed) {
    finish_task(TaskState::kFailed, Outcome::kActionFailed, fmt::format("action {} failed{}{}", result.name,
                                                result.message.empty() ? "" : ": ", result.message));
    return;
  }
  ++action_index_;
  run_next_action();
}

void Executor::on_interruptible_changed(bool interruptible) {
  robot_interruptible_ = interruptible;
  if (!interruptible || !current_) return;
  if (cancel_pending_ && interruptible_now()) {
    const std::string reason = *std::exchange(cancel_pending_, std::nullopt);
    stop_current(CancelIntent::kCancel, Outcome::kCancelled, reason);
    return;
  }
  if (overrun_pending_) {
    const auto [why, reason] = *overrun_pending_;
    overrun_pending_.reset();
    monitor_fired(why, reason);
    return;
  }
  if (!on_demand_.empty() && book_.at(*current_).task.kind == TaskKind::kStandard &&
      (phase_ == Phase::kNavigating || phase_ == Phase::kActing))
    preempt_for(Outcome::kPreemptedOnDemand, fmt::format("preempted by an on-demand task: {}", on_demand_.front()),
                {});
}

TimerId Executor::arm_monitor(CancelIntent why, const char* what, const char* of, Duration expected, double factor,
                              Duration slack) {
  const Duration limit = std::chrono::duration_cast<Duration>(expected * factor) + slack;
  const std::string reason = fmt::format("{} after {}, the limit is {} x {} {} + {}", what, minutes_text(limit),
                                         factor, of, minutes_text(expected), minutes_text(slack));
  TimerId* slot = why == CancelIntent::kNavigationOverrun ? &nav_monitor_ : &action_monitor_;
  MonitorDue* due = why == CancelIntent::kNavigationOverrun ? &nav_due_ : &action_due_;
  *due = {.at = clock_.now() + limit, .reason = reason, .left = std::nullopt};
  return clock_.schedule_after(limit, [this, why, reason, slot] {
    *slot = 0;
    monitor_fired(why, reason);
  });
}

// Monitors stand still while the robot is in fault: the time left is kept and runs on when it is
// ready again.
void Executor::suspend_monitors() {
  const Time now = clock_.now();
  for (auto [slot, due] : {std::pair{&nav_monitor_, &nav_due_}, std::pair{&action_monitor_, &action_due_}}) {
    if (*slot == 0) continue;
    clock_.cancel(*slot);
    *slot = 0;
    due->left = due->at - now;
  }
}

void Executor::resume_monitors() {
  for (auto [why, slot, due] : {std::tuple{CancelIntent::kNavigationOverrun, &nav_monitor_, &nav_due_},
                                std::tuple{CancelIntent::kActionOverrun, &action_monitor_, &action_due_}}) {
    if (!due->left) continue;
    const Duration left = *due->left;
    const std::string reason = due->reason;
    *due = {.at = clock_.now() + left, .reason = reason, .left = std::nullopt};
    *slot = clock_.schedule_after(left, [this, why, reason, slot] {
      *slot = 0;
      monitor_fired(why, reason);
    });
  }
}

void Executor::monitor_fired(CancelIntent why, const std::string& reason) {
  if (!current_) return;
  if (!interruptible_now()) {
    if (!overrun_pending_)
      book_.note(*current_, "overrun", Outcome::kOverrunHeld, reason + "; the task is not interruptible now, so it goes on");
    overrun_pending_ = std::make_pair(why, reason);
    return;
  }
  cancel_intent_ = why;
  cancel_outcome_ = why == CancelIntent::kNavigationOverrun ? Outcome::kNavigationOverrun : Outcome::kActionOverrun;
  cancel_reason_ = reason;
  if (robot_.busy())
    robot_.cancel();
  else
    handle_cancelled();
}

void Executor::preempt_for(Outcome outcome, const std::string& reason, std::vector<TaskId> then_schedule) {
  if (!current_ || cancel_intent_ == CancelIntent::kPreempt || cancel_intent_ == CancelIntent::kCancel) return;
  after_cancel_schedule_ = std::move(then_schedule);
  stop_current(CancelIntent::kPreempt, outcome, reason);
}

// Ends what the robot does for the current task; handle_cancelled() finishes the job once the
// robot has answered (at once when it is between commands).
void Executor::stop_current(CancelIntent intent, Outcome outcome, const std::string& reason) {
  cancel_intent_ = intent;
  cancel_outcome_ = outcome;
  cancel_reason_ = reason;
  if (robot_.busy())
    robot_.cancel();
  else
    handle_cancelled();
}

void Executor::handle_cancelled() {
  const CancelIntent intent = cancel_intent_;
  const Outcome outcome = cancel_outcome_;
  const std::string reason = cancel_reason_;
  cancel_intent_ = CancelIntent::kNone;
  cancel_outcome_ = Outcome::kNone;
  cancel_reason_.clear();
  switch (intent) {
    case CancelIntent::kNavigationOverrun:
    case CancelIntent::kActionOverrun:
      finish_task(TaskState::kFailed, outcome, reason);
      return;
    case CancelIntent::kCancel:
      finish_task(TaskState::kCancelled, outcome, reason);
      return;
    case CancelIntent::kLeaveDockTrip:
      phase_ = Phase::kIdle;
      next();
      return;
    case CancelIntent::kNone:  // the robot stopped by itself
      if (current_) {
        finish_task(TaskState::kFailed, Outcome::kActionFailed, "stopped by the robot");
      } else {
        phase_ = Phase::kIdle;
        next();
      }
      return;
    case CancelIntent::kPreempt:
      break;
  }
  // Preempted: the task keeps its id and goes back to the queue, to be scheduled again.
  const TaskId id = *current_;
  clear_timers();
  TaskRecord& r = book_.at(id);
  if (r.started) stats_.busy += clock_.now() - *r.started;
  current_.reset();
  phase_ = Phase::kIdle;
  robot_interruptible_ = true;
  overrun_pending_.reset();
  cancel_pending_.reset();
  std::vector<TaskId> again = std::move(after_cancel_schedule_);
  after_cancel_schedule_.clear();
  requeue_preempted(id, outcome, reason);
  if (book_.at(id).state == TaskState::kQueued) again.push_back(id);
  if (!again.empty()) reschedule(std::move(again), "after preempting " + id);
  next();
}

void Executor::requeue_preempted(const TaskId& id, Outcome outcome, const std::string& reason) {
  const Task& task = book_.at(id).task;
  if (task.kind == TaskKind::kStandard && clock_.now() + task.duration <= task.window->deadline) {
    book_.transition(id, TaskState::kQueued, outcome, reason + "; back in the queue");
    return;
  }
  book_.transition(id, TaskState::kFailed, outcome, reason + "; its window no longer allows it");
}

void Executor::finish_task(TaskState state, Outcome outcome, const std::string& reason) {
  const TaskId id = *current_;
  clear_timers();
  TaskRecord& r = book_.at(id);
  if (r.started) stats_.busy += clock_.now() - *r.started;
  book_.transition(id, state, outcome, reason);
  log_battery();
  current_.reset();
  phase_ = Phase::kIdle;
  robot_interruptible_ = true;
  overrun_pending_.reset();
  cancel_pending_.reset();
  if (state == TaskState::kFailed || state == TaskState::kCancelled) reschedule({}, "task " + id + " " + to_string(state));
  next();
}

void Executor::clear_timers() {
  for (TimerId* t : {&wait_timer_, &nav_monitor_, &action_monitor_}) {
    if (*t != 0) clock_.cancel(*t);
    *t = 0;
  }
  nav_due_.left.reset();
  action_due_.left.reset();
}

}  // namespace rondo::exec
