// The executor's calls to the scheduler: build a schedule::Problem of the pending standard tasks
// from where and when the robot is next free, run trySchedule/drop, and apply the answer.
#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "rondo/exec/executor.h"
#include "rondo/schedule/stop_condition.h"
#include "rondo/schedule/try_schedule.h"

namespace rondo::exec {
namespace {

Outcome drop_outcome(schedule::DropCause cause) {
  switch (cause) {
    case schedule::DropCause::kUnreachable: return Outcome::kOutOfReach;
    case schedule::DropCause::kHigherPriority: return Outcome::kDroppedForHigherPriority;
    case schedule::DropCause::kLowestPriority: return Outcome::kDroppedLowestPriority;
    case schedule::DropCause::kDoesNotFit: break;
  }
  return Outcome::kDoesNotFit;
}

}  // namespace

std::pair<map::NodeIndex, Time> Executor::free_at() const {
  const Time now = clock_.now();
  map::NodeIndex here = robot_.location();
  Time t = now;
  // Runs `task` after what is already planned: from `here` at `t`, or, when it is acting since
  // `acting_since`, until its processing time is over.
  const auto run = [&](const Task& task, std::optional<Time> acting_since) {
    const map::NodeIndex start = task.start_node.empty() ? here : *map_.find_node(task.start_node);
    if (acting_since) {
      t = std::max(now, *acting_since + task.duration);
    } else {
      Time s = t + travel_->travel(here, start, t);
      if (task.window) s = std::max(s, task.window->release);
      t = s + task.duration;
    }
    here = task.end_node.empty() ? start : *map_.find_node(task.end_node);
  };
  if (current_ && (phase_ == Phase::kNavigating || phase_ == Phase::kActing))
    run(book_.at(*current_).task, phase_ == Phase::kActing ? std::optional<Time>(acting_start_) : std::nullopt);
  for (const TaskId& id : on_demand_) run(book_.at(id).task, std::nullopt);
  return {here, t};
}

std::vector<TaskId> Executor::reoffer_deferred() {
  std::vector<TaskId> still;
  const Time now = clock_.now();
  for (const TaskId& id : deferred_) {
    TaskRecord& r = book_.at(id);
    if (r.state != TaskState::kQueued || !r.dropped_for_now) continue;
    if (now + r.task.duration <= r.task.window->deadline) {
      still.push_back(id);
      continue;
    }
    const auto [outcome, reason] = *r.dropped_for_now;
    book_.transition(id, TaskState::kDropped, outcome, reason);
  }
  deferred_ = still;
  return still;
}

void Executor::reschedule(std::vector<TaskId> new_ids, const std::string& why) {
  const std::vector<TaskId> offered_again = reoffer_deferred();
  std::vector<TaskId> ids;
  if (phase_ == Phase::kWaiting && current_) ids.push_back(*current_);  // waiting = still pending
  for (const TaskId& id : schedule_)
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  const std::size_t old_count = ids.size();
  for (const TaskId& id : new_ids)
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  const std::size_t first_deferred = ids.size();
  for (const TaskId& id : offered_again)
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  if (ids.empty()) {
    schedule_.clear();
    return;
  }
  const auto [here, free] = free_at();

  schedule::Problem problem;
  std::vector<map::NodeIndex> nodes{here};
  std::map<map::NodeIndex, schedule::LocationIndex> location{{here, 0}};
  const auto location_of = [&](const std::string& name) {
    const map::NodeIndex n = *map_.find_node(name);
    auto [it, inserted] = location.emplace(n, nodes.size());
    if (inserted) nodes.push_back(n);
    return it->second;
  };
  for (const TaskId& id : ids) {
    const Task& t = book_.at(id).task;
    const schedule::LocationIndex start = location_of(t.start_node);
    problem.tasks.push_back({.id = id,
                             .release = t.window->release,
                             .deadline = t.window->deadline,
                             .duration = t.duration,
                             .priority = t.priority,
                             .start_location = start,
                             .end_location = t.end_node.empty() ? start : location_of(t.end_node)});
  }
  for (map::NodeIndex n : nodes) problem.location_names.push_back(map_.node(n).name);
  problem.robot = {.location = 0, .time = free};
  problem.travel = std::make_shared<MapTravel>(*travel_, nodes);

  schedule::TryScheduleRequest request{.problem = std::move(problem), .new_tasks = {}, .zone = zone_};
  for (std::size_t i = old_count; i < ids.size(); ++i) request.new_tasks.push_back(i);
  for (std::size_t i = first_deferred; i < ids.size(); ++i) request.cannot_preempt.push_back(i);
  if (current_ && (phase_ == Phase::kNavigating || phase_ == Phase::kActing)) {
    const Task& t = book_.at(*current_).task;
    // An on-demand task is never given up for scheduled work.
    request.running = schedule::RunningTask{*current_, t.priority,
                                            t.kind == TaskKind::kStandard && interruptible_now()};
  }
  schedule::PollBudgetStop stop(options_.scheduler_polls);
  schedule::TryScheduleResult result = schedule::try_schedule(request, solver_, stop, rng_);
  stats_.schedules += result.attempts;
  if (result.outcome == schedule::TryScheduleOutcome::kOldTasksInfeasible) {
    // What was planned no longer fits (a task overran, an on-demand task came first): every task
    // competes again, and the lowest priorities give way.
    request.new_tasks.clear();
    for (std::size_t i = 0; i < ids.size(); ++i) request.new_tasks.push_back(i);
    schedule::PollBudgetStop again(options_.scheduler_polls);
    result = schedule::try_schedule(request, solver_, again, rng_);
    stats_.schedules += result.attempts;
  }
  if (result.outcome == schedule::TryScheduleOutcome::kPreemptRunning) {
    preempt_for(Outcome::kOutranked, "outranked by new tasks: " + result.preempt_reason, std::move(new_ids));
    return;
  }
  apply_schedule(ids, result.schedule, why);
}

void Executor::apply_schedule(const std::vector<TaskId>& ids, const schedule::Schedule& s, const std::string& why) {
  schedule_.clear();
  for (const schedule::ScheduledTask& e : s.entries) {
    const TaskId& id = ids[e.task];
    TaskRecord& r = book_.at(id);
    // The event log shows every (re)scheduling that moved a task, and why it happened.
    if (r.planned_start != e.start)
      book_.note(id, "scheduled", Outcome::kScheduled, fmt::format("planned start {} ({}: position {} of {})", fmt_time(e.start), why,
                                        schedule_.size() + 1, s.entries.size()));
    r.planned_start = e.start;
    r.planned_end = e.end;
    if (r.dropped_for_now) {
      book_.note(id, "re-offered", Outcome::kScheduled,
                 fmt::format("fits again after its drop: planned start {} ({})", fmt_time(e.start), why));
      r.dropped_for_now.reset();
      std::erase(deferred_, id);
    }
    schedule_.push_back(id);  // a task being waited for too: kick() reconsiders it
  }
  for (const schedule::DroppedTask& d : s.dropped) {
    const TaskId& id = ids[d.task];
    if (phase_ == Phase::kWaiting && current_ && *current_ == id) {
      clock_.cancel(wait_timer_);
      wait_timer_ = 0;
      stats_.waiting += clock_.now() - wait_start_;
      current_.reset();
      phase_ = Phase::kIdle;
    }
    TaskRecord& r = book_.at(id);
    r.planned_start.reset();
    r.planned_end.reset();
    // Dropped for now: offered again at every reschedule while its window can still be met.
    const Outcome outcome = drop_outcome(d.cause);
    if (r.state != TaskState::kQueued) book_.transition(id, TaskState::kQueued, outcome, d.reason);
    if (!r.dropped_for_now) {
      book_.note(id, "dropped for now", outcome, d.reason);
      // When its window can no longer be met it is dropped for good, whatever else happens.
      clock_.schedule_at(r.task.window->deadline - r.task.duration + milliseconds(1),
                         [this] { (void)reoffer_deferred(); });
    }
    r.dropped_for_now = std::make_pair(outcome, d.reason);
    if (std::find(deferred_.begin(), deferred_.end(), id) == deferred_.end()) deferred_.push_back(id);
  }
}

}  // namespace rondo::exec
