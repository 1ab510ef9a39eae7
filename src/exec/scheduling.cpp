#include "scheduling.h"

#include <map>
#include <memory>

#include "rondo/map/map_geometry.h"
#include "rondo/schedule/stop_condition.h"

namespace rondo::exec {

Outcome drop_outcome(schedule::DropCause cause) {
  switch (cause) {
    case schedule::DropCause::kUnreachable: return Outcome::kOutOfReach;
    case schedule::DropCause::kHigherPriority: return Outcome::kDroppedForHigherPriority;
    case schedule::DropCause::kLowestPriority: return Outcome::kDroppedLowestPriority;
    case schedule::DropCause::kDoesNotFit: break;
  }
  return Outcome::kDoesNotFit;
}

void set_travel(schedule::Problem& problem, const TravelCache& cache, const std::vector<map::NodeIndex>& nodes,
                std::optional<double> risk_alpha) {
  problem.travel = std::make_shared<SchedulerTravel>(cache, nodes);
  problem.window_travel.reset();
  if (risk_alpha) problem.window_travel = std::make_shared<SchedulerQuantileTravel>(cache, nodes, 1.0 - *risk_alpha);
}

Result<schedule::TryScheduleResult> schedule_pending(const ScheduleInputs& in, const PendingTasks& pending,
                                             map::NodeIndex here, Time free,
                                             std::optional<schedule::RunningTask> running) {
  RONDO_ASSIGN_OR_RETURN(PendingProblem p, pending_problem(in, pending, here, free, std::move(running)));
  return solve_pending(p.request, in.scheduler, in.polls, nullptr, in.rng);
}

Result<PendingProblem> pending_problem(const ScheduleInputs& in, const PendingTasks& pending, map::NodeIndex here,
                                       Time free, std::optional<schedule::RunningTask> running) {
  schedule::Problem problem;
  std::vector<map::NodeIndex> nodes{here};
  std::map<map::NodeIndex, schedule::LocationIndex> location{{here, 0}};
  const auto location_of = [&](const std::string& name) {
    const map::NodeIndex n = *in.map.find_node(name);
    auto [it, inserted] = location.emplace(n, nodes.size());
    if (inserted) nodes.push_back(n);
    return it->second;
  };
  std::map<TaskId, std::size_t> index;
  for (std::size_t i = 0; i < pending.ids.size(); ++i) index.emplace(pending.ids[i], i);
  for (const TaskId& id : pending.ids) {
    const TaskRecord& r = in.book.at(id);
    const Task& t = r.task;
    const schedule::LocationIndex start = location_of(t.start_node);
    problem.tasks.push_back({.id = id,
                             .release = r.release(),
                             .deadline = t.window->deadline,
                             .duration = r.remaining(),
                             .priority = t.priority,
                             .start_location = start,
                             .end_location = t.end_node.empty() ? start : location_of(t.end_node)});
    schedule::ProblemTask& pt = problem.tasks.back();
    if (t.delivery)
      pt.transfer = schedule::ItemTransfer{
          .job = t.delivery->job,
          .action = t.delivery->role == DeliveryRole::kPickup ? schedule::ItemAction::kPickup
                                                              : schedule::ItemAction::kDrop,
          .appearance = t.delivery->appearance,
          .load = t.delivery->load};
    for (const TaskId& a : t.after)
      if (const auto it = index.find(a); it != index.end()) pt.after.push_back(it->second);
  }
  std::optional<ChargePlan> battery;
  if (in.battery) {
    const BatteryInputs& b = *in.battery;
    battery = ChargePlan{.estimator = b.estimator, .level = b.level, .reserve = b.reserve, .margin = b.margin,
                         .drift_per_hour = b.drift_per_hour, .drift_variance_per_hour = b.drift_variance_per_hour,
                         .dock = location_of(in.map.node(b.dock).name),
                         .dock_when_waiting_over = b.dock_when_waiting_over};
    battery->metres.reserve(nodes.size() * nodes.size());
    for (map::NodeIndex from : nodes) {
      const std::vector<double> d = map::shortest_metres(in.map, from);
      for (map::NodeIndex to : nodes) battery->metres.push_back(d[to]);
    }
  }
  problem.robot.capacity = in.capacity;
  for (const OnBoard& o : in.on_board)
    problem.robot.on_board.push_back({.job = o.job, .appearance = o.appearance, .load = o.load});
  for (map::NodeIndex n : nodes) problem.location_names.push_back(in.map.node(n).name);
  problem.robot.location = 0;
  problem.robot.time = free;
  set_travel(problem, in.travel, nodes, in.risk_alpha);

  RONDO_RETURN_IF_ERROR(schedule::validate(problem));
  PendingProblem out{.request = {.problem = std::move(problem), .new_tasks = {}, .zone = in.zone},
                     .nodes = std::move(nodes),
                     .risk_alpha = in.risk_alpha,
                     .battery = std::move(battery)};
  schedule::TryScheduleRequest& request = out.request;
  for (std::size_t i = pending.old_count; i < pending.ids.size(); ++i) request.new_tasks.push_back(i);
  for (std::size_t i = pending.first_reoffered; i < pending.ids.size(); ++i) request.cannot_preempt.push_back(i);
  request.running = std::move(running);
  return out;
}

schedule::TryScheduleResult solve_pending(schedule::TryScheduleRequest& request, schedule::Scheduler& scheduler,
                                          std::int64_t polls, const schedule::StopCondition* also,
                                          std::mt19937_64& rng) {
  schedule::PollBudgetStop budget(polls);
  std::vector<const schedule::StopCondition*> parts{&budget};
  if (also) parts.push_back(also);
  schedule::TryScheduleResult result = schedule::try_schedule(request, scheduler, schedule::AnyStop(parts), rng);
  if (result.outcome != schedule::TryScheduleOutcome::kOldTasksInfeasible) return result;
  // What was planned no longer fits (a task overran, an on-demand task came first): every task
  // competes again, and the lowest priorities give way.
  const int attempts = result.attempts;
  request.new_tasks.clear();
  for (std::size_t i = 0; i < request.problem.tasks.size(); ++i) request.new_tasks.push_back(i);
  schedule::PollBudgetStop again(polls);
  parts[0] = &again;
  result = schedule::try_schedule(request, scheduler, schedule::AnyStop(parts), rng);
  result.attempts += attempts;
  return result;
}

PlannedAnswer solve_planned(PendingProblem& problem, schedule::Scheduler& scheduler, std::int64_t polls,
                            const schedule::StopCondition* also, std::mt19937_64& rng) {
  return plan_charges(problem.request, problem.battery ? &*problem.battery : nullptr,
                      [&](schedule::TryScheduleRequest& r) { return solve_pending(r, scheduler, polls, also, rng); });
}

}  // namespace rondo::exec
