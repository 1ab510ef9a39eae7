// The answer of the fleet scheduler: one route per robot (tasks in order with their times), the
// tasks left out, and the objective's parts.
//
//   FleetPlan plan = FleetScheduler{{.seed = 7}}.solve(problem, stop);
//   for (std::size_t r = 0; r < plan.routes.size(); ++r)
//     for (const ScheduledTask& e : plan.routes[r]) ...;   // e.task indexes problem.tasks
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rondo/schedule/fleet_problem.h"
#include "rondo/schedule/schedule.h"

namespace rondo::schedule {

struct FleetPlan {
  SolveStatus status = SolveStatus::kTimeout;  // kFeasible when every task is planned
  std::vector<std::vector<ScheduledTask>> routes{};  // one per robot, maybe empty
  std::vector<DroppedTask> dropped{};
  double objective = 0;             // the problem's objective, in seconds (or distance units)
  std::size_t vehicles = 0;         // robots with at least one task
  double distance = 0;              // FleetProblem::distance_between summed, dock legs included
  double seconds_to_first = 0;      // filled by callers that measure time
  double seconds = 0;

  std::size_t planned() const;
};

// Times given task orders on each robot (leave at once, wait for the release) and fills the plan's
// times, distance, vehicles and objective; the tasks in no route are dropped with `reason`. An
// error names the first task that misses its window or the robot that misses its dock deadline.
Result<FleetPlan> time_fleet_routes(const FleetProblem& problem, const std::vector<std::vector<std::size_t>>& orders,
                                    const std::string& reason = "no robot can fit it");

}  // namespace rondo::schedule
