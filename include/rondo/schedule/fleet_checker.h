// An independent referee for fleet plans, in the manner of check_schedule: it recomputes every
// route's times from the robots' states and the travel oracles, sharing no code with the solver,
// and lists every violation it finds.
//
//   FleetCheckReport r = check_fleet_plan(problem, plan);
//   EXPECT_TRUE(r.ok()) << r.summary();
//
// Checked: one route per robot; each task in at most one route and either planned or dropped
// (with a reason), never both; depart == previous end (or free_from); arrival >= depart + the
// robot's travel; start >= arrival and >= release; end == start + duration; the deadline; the
// dock's deadline; the task's action among the robot's; the pin; a pickup and its drop on the same
// robot, the pickup first, both or neither planned; capacity; never two same-looking items on
// board; `after`: the earlier task planned, on the same robot, and ended before the later one
// starts; the reported
// vehicles, distance and objective equal the recomputed ones.
#pragma once

#include <string>
#include <vector>

#include "rondo/schedule/fleet_plan.h"
#include "rondo/schedule/fleet_problem.h"

namespace rondo::schedule {

struct FleetCheckReport {
  std::vector<std::string> violations;
  std::vector<std::string> dropped;  // ids of the tasks left out
  double recomputed_objective = 0;
  double recomputed_distance = 0;
  bool ok() const { return violations.empty(); }
  std::string summary() const;
};

FleetCheckReport check_fleet_plan(const FleetProblem& problem, const FleetPlan& plan);

}  // namespace rondo::schedule
