#include "rondo/schedule/fleet_plan.h"

#include <algorithm>

#include <fmt/format.h>

namespace rondo::schedule {

std::size_t FleetPlan::planned() const {
  std::size_t n = 0;
  for (const auto& r : routes) n += r.size();
  return n;
}

Result<FleetPlan> time_fleet_routes(const FleetProblem& p, const std::vector<std::vector<std::size_t>>& orders,
                                    const std::string& reason) {
  FleetPlan plan;
  plan.routes.resize(p.robots.size());
  std::vector<bool> planned(p.tasks.size(), false);
  double sum_ends = 0, lateness = 0, drops = 0;
  for (std::size_t r = 0; r < orders.size() && r < p.robots.size(); ++r) {
    const FleetRobot& robot = p.robots[r];
    Time now = robot.free_from;
    LocationIndex here = robot.location;
    for (std::size_t i : orders[r]) {
      const FleetTask& f = p.tasks[i];
      const ProblemTask& t = f.task;
      ScheduledTask e{.task = i, .depart = now};
      e.travel = robot_travel(p, r, here, t.start_location, now);
      e.arrival = now + e.travel;
      e.start = std::max(e.arrival, t.release);
      e.waiting = e.start - e.arrival;
      e.end = e.start + t.duration;
      if (e.start > t.latest_start())
        return Error::invalid(fmt::format("robot '{}': task '{}' starts at {}, after its latest start {}", robot.name,
                                          t.id, format_time(e.start), format_time(t.latest_start())));
      plan.distance += p.distance_between(here, t.start_location);
      sum_ends += to_seconds(e.end - robot.free_from);
      if (f.due && e.end > *f.due) lateness += to_seconds(e.end - *f.due) * (1 + t.priority);
      planned[i] = true;
      plan.routes[r].push_back(e);
      now = e.end;
      here = t.end_location;
    }
    if (!orders[r].empty()) {
      ++plan.vehicles;
      if (robot.end) {
        const Time back = now + robot_travel(p, r, here, robot.end->location, now);
        plan.distance += p.distance_between(here, robot.end->location);
        if (back > robot.end->deadline)
          return Error::invalid(fmt::format("robot '{}': back at its dock at {}, after {}", robot.name, format_time(back),
                                            format_time(robot.end->deadline)));
      }
    }
  }
  for (std::size_t i = 0; i < p.tasks.size(); ++i)
    if (!planned[i]) {
      plan.dropped.push_back({.task = i, .reason = reason, .cause = DropCause::kDoesNotFit});
      drops += p.costs.drop_seconds * (1 + p.tasks[i].task.priority);
    }
  plan.objective = p.objective == FleetObjective::kSumOfEnds
                       ? sum_ends + p.costs.lateness_per_second * lateness + drops
                       : plan.distance + drops;
  plan.status = SolveStatus::kFeasible;  // a plan; its drops are listed
  return plan;
}

}  // namespace rondo::schedule
