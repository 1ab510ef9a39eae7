// Allocation by the fleet scheduler (issue 39 behind issue 38's Allocator): the new units and every
// eligible robot's planned tasks become one schedule::FleetProblem, schedule::FleetScheduler
// solves it on a poll budget, and each unit goes to the robot whose route holds it. The robot then
// schedules what it was given with its own scheduler, as under GreedyAllocator.
//
//   fleet::Fleet fleet(clock, map, store, zone, options, {},
//                      std::make_unique<FleetSchedulerAllocator>(FleetSchedulerAllocatorOptions{
//                          .speed_factors = {{"r3", 0.9}}}));
//
// The problem (docs/fleet.md, "Allocation"):
// - a robot: where and when it is next free (Executor::free_at), its capacity, its speed factor
//   (learned: Building::speeds; before the first refit that has seen it, declared in the options;
//   travel is the building's TravelCache, in the fleet's standard time, divided by it); robots start the problem empty
//   (an object on board is not counted against the capacity: its drop is a plain task there) and have no dock deadline;
// - its planned tasks (Executor::activity().planned), pinned to it: what a robot has planned
//   stays there; a delivery job whose halves are both planned there stays a pair;
// - the new units: a delivery job's halves as a pickup and its drop; a unit eligible on one robot
//   pinned to it; one eligible on some robots only takes an action that only those list; a
//   delivery passes over a robot carrying a look-alike or full (room_on_board), when another may
//   take it.
// Decided outside the solver: an on-demand unit goes where GreedyAllocator puts it (the robot
// that can be there soonest), and so do a unit eligible on one robot only, a spec task and a unit
// the plan leaves out (the greedy's answer for the whole batch, with its `fits` and `why`). A unit
// the plan holds fits, and its `why` gives its place on the robot's route.
// Deterministic: the solver's seed, and a budget counted in polls (never the wall clock), so a
// run of `rondo run` gives the same allocation on any machine and under any load.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rondo/fleet/allocator.h"
#include "rondo/schedule/fleet_plan.h"
#include "rondo/schedule/fleet_problem.h"

namespace rondo::fleet {

struct FleetSchedulerAllocatorOptions {
  std::uint64_t seed = 1;
  // Large-neighbourhood-search iterations after the construction (which takes one poll per
  // request): the poll budget is requests + this. docs/fleet.md gives the measured trade-off.
  std::int64_t search_polls = 300;
  // Per robot name, the declared factor its travel is divided by (a simulated robot's `speed`) until
  // a refit has learned its own (Building::speeds); 1 if absent.
  std::map<std::string, double> speed_factors{};
};

// The fleet problem of one allocation, and how it maps back to the fleet.
struct AllocationProblem {
  schedule::FleetProblem problem;
  std::vector<std::size_t> robots;                   // problem robot i is the fleet's robots[i]
  std::vector<std::vector<std::size_t>> unit_tasks;  // per unit, its problem tasks (empty: not in it)
  std::size_t planned_tasks = 0;                     // the robots' planned tasks come first
};

// Builds the problem of `units` (precondition: each has a non-empty `eligible`). A unit is left
// out (empty unit_tasks) when it is on-demand, or one of its tasks has no window or no start node
// (a spec task). Robots: those eligible for a unit in the problem, in the fleet's order.
AllocationProblem allocation_problem(const std::vector<AllocationUnit>& units,
                                     const std::vector<const exec::Executor*>& robots, const exec::Building& building,
                                     const std::map<std::string, double>& speed_factors);

class FleetSchedulerAllocator final : public Allocator {
 public:
  explicit FleetSchedulerAllocator(FleetSchedulerAllocatorOptions options = {}) : options_(std::move(options)) {}
  std::vector<Allocation> allocate(const std::vector<AllocationUnit>& units,
                                   const std::vector<const exec::Executor*>& robots,
                                   const exec::Building& building) override;
  // The last allocation that ran the solver: its problem and plan (for tests and the report of a
  // choice); nothing before the first.
  const std::optional<AllocationProblem>& last_problem() const { return last_problem_; }
  const std::optional<schedule::FleetPlan>& last_plan() const { return last_plan_; }

 private:
  FleetSchedulerAllocatorOptions options_;
  std::optional<AllocationProblem> last_problem_;
  std::optional<schedule::FleetPlan> last_plan_;
};

}  // namespace rondo::fleet
