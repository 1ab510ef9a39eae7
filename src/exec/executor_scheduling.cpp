// The executor's calls to the scheduler: build a schedule::Problem of the pending standard tasks
// from where and when the robot is next free, run trySchedule/drop, and apply the answer.
#include <fmt/format.h>

#include <algorithm>
#include <map>

#include "rondo/exec/executor.h"
#include "rondo/schedule/stop_condition.h"
#include "rondo/schedule/try_schedule.h"

namespace rondo::exec {

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
    run(tasks_.at(*current_).task, phase_ == Phase::kActing ? std::optional<Time>(acting_start_) : std::nullopt);
  for (const TaskId& id : on_demand_) run(tasks_.at(id).task, std::nullopt);
  return {here, t};
}

void Executor::reschedule(std::vector<TaskId> new_ids, const std::string& why) {
  std::vector<TaskId> ids;
  if (phase_ == Phase::kWaiting && current_) ids.push_back(*current_);  // waiting = still pending
  for (const TaskId& id : schedule_)
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  const std::size_t old_count = ids.size();
  for (const TaskId& id : new_ids)
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
    const Task& t = tasks_.at(id).task;
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

  schedule::TryScheduleRequest request{.problem = std::move(problem), .new_tasks = {}};
  for (std::size_t i = old_count; i < ids.size(); ++i) request.new_tasks.push_back(i);
  if (current_ && (phase_ == Phase::kNavigating || phase_ == Phase::kActing)) {
    const Task& t = tasks_.at(*current_).task;
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
    preempt_for("outranked by new tasks: " + result.preempt_reason, std::move(new_ids));
    return;
  }
  apply_schedule(ids, result.schedule, why);
}

void Executor::apply_schedule(const std::vector<TaskId>& ids, const schedule::Schedule& s, const std::string& why) {
  schedule_.clear();
  for (const schedule::ScheduledTask& e : s.entries) {
    const TaskId& id = ids[e.task];
    TaskRecord& r = tasks_.at(id);
    // The event log shows every (re)scheduling that moved a task, and why it happened.
    if (r.planned_start != e.start)
      note(id, "scheduled", fmt::format("planned start {} ({}: position {} of {})", fmt_time(e.start), why,
                                        schedule_.size() + 1, s.entries.size()));
    r.planned_start = e.start;
    r.planned_end = e.end;
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
    tasks_.at(id).planned_start.reset();
    tasks_.at(id).planned_end.reset();
    transition(id, TaskState::kDropped, d.reason);
  }
}

}  // namespace rondo::exec
