// Allocation by the fleet scheduler (issue 39 behind issue 38's Allocator): the new units and every
// eligible robot's planned tasks become one schedule::FleetProblem, schedule::FleetScheduler
// solves it on a poll budget, and each unit goes to the robot whose route holds it. The robot then
// schedules what it was given with its own scheduler, as under GreedyAllocator.
//
// Two ways to the plan (docs/fleet.md, "The two ways to a plan"): a large fleet (at least
// `insert_from_planned` planned tasks) given a few units (at most `insert_units`) keeps every
// robot's own planned order as its route and inserts the new units into those routes, with a short
// repair around each (FleetScheduler::insert); anything else, or an insertion that leaves a unit
// out, is solved whole (FleetScheduler::solve: construction, then `search_polls` iterations). Both
// read only the fleet's state as it is now, so an answer never depends on the allocations before
// it; what is kept between allocations is the travel oracle of the insertions (HeldTravel), whose
// values are the building's cache's whatever it holds.
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
#include <utility>
#include <vector>

#include "rondo/fleet/allocation_problem.h"
#include "rondo/fleet/allocator.h"
#include "rondo/fleet/held_travel.h"
#include "rondo/schedule/fleet_plan.h"
#include "rondo/schedule/fleet_problem.h"

namespace rondo::fleet {

struct FleetSchedulerAllocatorOptions {
  std::uint64_t seed = 1;
  // Large-neighbourhood-search iterations after the construction (which takes one poll per
  // request): the poll budget is requests + this. docs/fleet.md gives the measured trade-off.
  std::int64_t search_polls = 300;
  // Insertion into the robots' own plans, in place of the whole solve, for a batch of at most
  // `insert_units` units in the problem when the robots hold at least `insert_from_planned` planned
  // tasks (below, the whole solve costs a few milliseconds and may reorder their plans better);
  // `insert_units` 0 turns it off. `repair_rounds`: ruin-and-recreate rounds around each unit.
  std::size_t insert_units = 4;
  std::size_t insert_from_planned = 200;
  std::size_t repair_rounds = 10;
  // Per robot name, the declared factor its travel is divided by (a simulated robot's `speed`) until
  // a refit has learned its own (Building::speeds); 1 if absent.
  std::map<std::string, double> speed_factors{};
};

// How the allocations so far were made (for tests and benches).
struct AllocationCounts {
  std::size_t solved = 0;     // the whole problem solved (a large batch, a small fleet)
  std::size_t inserted = 0;   // the units inserted into the robots' plans
  std::size_t fell_back = 0;  // an insertion left a unit out, and the whole solve answered
};

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
  const AllocationCounts& counts() const { return counts_; }
  const HeldTravel& held_travel() const { return held_travel_; }

 private:
  // The plan of the problem's units by insertion into the robots' plans; nullopt when the fast way
  // does not apply or leaves a unit out.
  std::optional<std::pair<AllocationProblem, schedule::FleetPlan>> insert_units(
      const std::vector<AllocationUnit>& units, const std::vector<const exec::Executor*>& robots,
      const exec::Building& building);
  std::optional<std::pair<AllocationProblem, schedule::FleetPlan>> solve_units(
      const std::vector<AllocationUnit>& units, const std::vector<const exec::Executor*>& robots,
      const exec::Building& building) const;

  FleetSchedulerAllocatorOptions options_;
  AllocationCounts counts_;
  HeldTravel held_travel_;
  std::optional<AllocationProblem> last_problem_;
  std::optional<schedule::FleetPlan> last_plan_;
};

}  // namespace rondo::fleet
