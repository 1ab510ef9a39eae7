// The executor running tasks: what to do next, waiting, running actions, the two monitors and
// preemption (navigation is in executor_navigation.cpp).
#include <fmt/format.h>

#include <algorithm>

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
      transition(id, TaskState::kQueued, "waiting interrupted: the schedule changed");
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
  if (phase_ != Phase::kIdle || robot_.busy()) return;
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
    const Task& task = tasks_.at(id).task;
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
      transition(id, TaskState::kFailed, reason);
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
      TaskRecord& r = tasks_.at(id);
      if (!r.started) r.started = now;
      transition(id, TaskState::kWaiting,
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
  TaskRecord& r = tasks_.at(id);
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
    finish_task(TaskState::kFailed,
                fmt::format("no route: from {} to {} at {}", map_.node(here).name, task.start_node, fmt_time(now)));
    return;
  }
  transition(id, TaskState::kNavigating,
             fmt::format("to {} from {}, expected travel {}", map_.node(target).name, map_.node(here).name,
                         minutes_text(expected)));
  begin_navigation(target, expected);
}

void Executor::start_actions() {
  const TaskId& id = *current_;
  const Task& task = tasks_.at(id).task;
  const Time now = clock_.now();
  phase_ = Phase::kActing;
  acting_start_ = now;
  action_index_ = 0;
  transition(id, TaskState::kActing,
             fmt::format("arrived at {} after {} (expected {}); expected processing {}", map_.node(nav_target_).name,
                         minutes_text(now - nav_start_), minutes_text(nav_expected_), minutes_text(task.duration)));
  action_monitor_ = arm_monitor(CancelIntent::kActionOverrun, "action overrun: still acting", "the processing time",
                                task.duration, options_.action_overrun, options_.action_slack);
  run_next_action();
}

void Executor::run_next_action() {
  const Task& task = tasks_.at(*current_).task;
  const std::size_t n = std::max<std::size_t>(1, task.actions.size());
  if (action_index_ >= n) {
    finish_task(TaskState::kSucceeded, fmt::format("done: {} of actions (expected {})",
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
  if (result.outcome == ActionOutcome::kFailed) {
    finish_task(TaskState::kFailed, fmt::format("action {} failed{}{}", result.name,
                                                result.message.empty() ? "" : ": ", result.message));
    return;
  }
  ++action_index_;
  run_next_action();
}

void Executor::on_interruptible_changed(bool interruptible) {
  robot_interruptible_ = interruptible;
  if (!interruptible || !current_) return;
  if (overrun_pending_) {
    const auto [why, reason] = *overrun_pending_;
    overrun_pending_.reset();
    monitor_fired(why, reason);
    return;
  }
  if (!on_demand_.empty() && tasks_.at(*current_).task.kind == TaskKind::kStandard &&
      (phase_ == Phase::kNavigating || phase_ == Phase::kActing))
    preempt_for(fmt::format("preempted by an on-demand task: {}", on_demand_.front()), {});
}

TimerId Executor::arm_monitor(CancelIntent why, const char* what, const char* of, Duration expected, double factor,
                              Duration slack) {
  const Duration limit = std::chrono::duration_cast<Duration>(expected * factor) + slack;
  const std::string reason = fmt::format("{} after {}, the limit is {} x {} {} + {}", what, minutes_text(limit),
                                         factor, of, minutes_text(expected), minutes_text(slack));
  TimerId* slot = why == CancelIntent::kNavigationOverrun ? &nav_monitor_ : &action_monitor_;
  return clock_.schedule_after(limit, [this, why, reason, slot] {
    *slot = 0;
    monitor_fired(why, reason);
  });
}

void Executor::monitor_fired(CancelIntent why, const std::string& reason) {
  if (!current_) return;
  if (!interruptible_now()) {
    if (!overrun_pending_)
      note(*current_, "overrun", reason + "; the task is not interruptible now, so it goes on");
    overrun_pending_ = std::make_pair(why, reason);
    return;
  }
  cancel_intent_ = why;
  cancel_reason_ = reason;
  if (robot_.busy())
    robot_.cancel();
  else
    handle_cancelled();
}

void Executor::preempt_for(const std::string& reason, std::vector<TaskId> then_schedule) {
  if (!current_ || cancel_intent_ == CancelIntent::kPreempt) return;
  after_cancel_schedule_ = std::move(then_schedule);
  cancel_intent_ = CancelIntent::kPreempt;
  cancel_reason_ = reason;
  if (robot_.busy())
    robot_.cancel();
  else
    handle_cancelled();
}

void Executor::handle_cancelled() {
  const CancelIntent intent = cancel_intent_;
  const std::string reason = cancel_reason_;
  cancel_intent_ = CancelIntent::kNone;
  cancel_reason_.clear();
  switch (intent) {
    case CancelIntent::kNavigationOverrun:
    case CancelIntent::kActionOverrun:
      finish_task(TaskState::kFailed, reason);
      return;
    case CancelIntent::kLeaveDockTrip:
      phase_ = Phase::kIdle;
      next();
      return;
    case CancelIntent::kNone:  // the robot stopped by itself
      if (current_) {
        finish_task(TaskState::kFailed, "stopped by the robot");
      } else {
        phase_ = Phase::kIdle;
        next();
      }
      return;
    case CancelIntent::kPreempt:
      break;
  }
  // Preempted: the task ends, and comes back as a new task when its window still allows it.
  const TaskId id = *current_;
  clear_timers();
  TaskRecord& r = tasks_.at(id);
  if (r.started) stats_.busy += clock_.now() - *r.started;
  transition(id, TaskState::kPreempted, reason);
  current_.reset();
  phase_ = Phase::kIdle;
  robot_interruptible_ = true;
  overrun_pending_.reset();
  std::vector<TaskId> again = std::move(after_cancel_schedule_);
  after_cancel_schedule_.clear();
  const Task& task = r.task;
  if (task.kind == TaskKind::kStandard && clock_.now() + task.duration <= task.window->deadline) {
    Task copy = task;
    const std::string base = id.substr(0, id.find('~'));
    copy.id = fmt::format("{}~{}", base, ++requeues_[base]);
    auto added = insert_tasks({std::move(copy)}, "preempted " + id);
    if (added) again.insert(again.end(), added->begin(), added->end());
  }
  if (!again.empty()) reschedule(std::move(again), "after preempting " + id);
  next();
}

void Executor::finish_task(TaskState state, const std::string& reason) {
  const TaskId id = *current_;
  clear_timers();
  TaskRecord& r = tasks_.at(id);
  if (r.started) stats_.busy += clock_.now() - *r.started;
  transition(id, state, reason);
  current_.reset();
  phase_ = Phase::kIdle;
  robot_interruptible_ = true;
  overrun_pending_.reset();
  if (state == TaskState::kFailed) reschedule({}, "task " + id + " failed");
  next();
}

void Executor::clear_timers() {
  for (TimerId* t : {&wait_timer_, &nav_monitor_, &action_monitor_}) {
    if (*t != 0) clock_.cancel(*t);
    *t = 0;
  }
}

}  // namespace rondo::exec
