// The fleet problem of one allocation under FleetSchedulerAllocator (docs/fleet.md, "Allocation"):
// the robots eligible for the new units, each robot's planned tasks pinned to it (in its planned
// order, so that a caller may keep that order as the robot's route), and the new units.
//
//   AllocationProblem ap = allocation_problem(units, robots, building, speed_factors);
//   FleetPlan plan = FleetScheduler{}.solve(ap.problem, stop);   // or insert(ap.problem, ap.orders, ...)
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rondo/exec/building.h"
#include "rondo/exec/executor.h"
#include "rondo/exec/map_travel.h"
#include "rondo/fleet/allocator.h"
#include "rondo/schedule/fleet_problem.h"

namespace rondo::fleet {

// The fleet problem of one allocation, and how it maps back to the fleet.
struct AllocationProblem {
  schedule::FleetProblem problem;
  std::vector<std::size_t> robots;                   // problem robot i is the fleet's robots[i]
  std::vector<std::vector<std::size_t>> unit_tasks;  // per unit, its problem tasks (empty: not in it)
  std::size_t planned_tasks = 0;                     // the robots' planned tasks come first
  // Per problem robot, its planned tasks' problem indices in its planned order.
  std::vector<std::vector<std::size_t>> orders;
};

// Builds the problem of `units` (precondition: each has a non-empty `eligible`). A unit is left
// out (empty unit_tasks) when it is on-demand, or one of its tasks has no window or no start node
// (a spec task). Robots: those eligible for a unit in the problem, in the fleet's order.
// Locations: the nodes the problem uses, with an oracle made for them; or, with `travel` (an
// oracle over every node of the map, HeldTravel), every map node is its own location.
AllocationProblem allocation_problem(const std::vector<AllocationUnit>& units,
                                     const std::vector<const exec::Executor*>& robots, const exec::Building& building,
                                     const std::map<std::string, double>& speed_factors,
                                     std::shared_ptr<const exec::SchedulerTravel> travel = nullptr);

// Whether a unit goes into the problem: not on-demand, and every task with a window that still
// leaves room for its work and a start node (no spec task).
bool in_allocation_problem(const AllocationUnit& unit, const map::TopoMap& map);

}  // namespace rondo::fleet
