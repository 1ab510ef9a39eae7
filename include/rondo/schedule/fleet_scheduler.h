// The fleet scheduler (issue 39): allocates and orders tasks across robots, anytime.
//
//   FleetScheduler solver({.seed = 7});
//   FleetPlan plan = solver.solve(problem, stop);                // stop: time, polls, cancel
//   FleetPlan next = solver.insert(problem_with_one_more, plan, new_task, PollBudgetStop(200));
//   FleetPlan kept = solver.insert(problem, robots_orders, {new_pickup, new_drop}, PollBudgetStop(20));
//
// How (docs/scheduling.md, "The fleet scheduler"):
// 1. regret-2 insertion builds a first plan (every request's best insertion per robot is cached
//    and recomputed only for the robot that changed);
// 2. for the hierarchical objective, route minimisation: a route is emptied into a pool and
//    large neighbourhood search tries to place the pool elsewhere, weighting the customers that
//    keep failing; the last plan with every task is kept;
// 3. large neighbourhood search until `stop`: remove requests (random, related, strings around a
//    seed in nearby routes, a whole route), put them back (greedy with blinks, or regret-2), and
//    accept by simulated annealing on a cyclic temperature schedule counted in iterations; the
//    best plan gets a relocate/2-opt* descent when it improves.
// One robot with the sum-of-ends objective: today's DefaultScheduler answers (exactly as good).
// Deterministic for a given seed and a deterministic stop condition: no decision reads a clock;
// `stop` is polled once per iteration (and once per request inserted while constructing).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>

#include "rondo/schedule/fleet_plan.h"
#include "rondo/schedule/fleet_problem.h"
#include "rondo/schedule/stop_condition.h"

namespace rondo::schedule {

// What the search has at a moment, for callers that time it (the CLI's time to the first
// feasible plan); the search's decisions never depend on it.
struct FleetProgress {
  std::size_t vehicles = 0;
  double distance = 0;
  double objective = 0;       // the search's cost (drops and robots priced in)
  std::size_t unplanned = 0;  // requests left out
  std::size_t iteration = 0;
};

struct FleetSchedulerOptions {
  std::uint64_t seed = 1;
  std::size_t route_min_iterations = 20000;  // per attempt to empty one more route
  std::size_t cycle_iterations = 50000;      // one cooling cycle of the annealing
  std::size_t repair_iterations = 10;        // after insert()
  bool improve = true;                       // off: construction only
  bool single_robot_default = true;          // one robot, sum of ends: DefaultScheduler
  // Called after the construction and at every new best plan.
  std::function<void(const FleetProgress&)> on_progress{};
};

class FleetScheduler {
 public:
  explicit FleetScheduler(FleetSchedulerOptions options = {}) : options_(options) {}
  // Precondition: validate_fleet(problem) succeeded. Never throws on a valid problem.
  FleetPlan solve(const FleetProblem& problem, const StopCondition& stop) const;
  // `problem` is the solved problem with task `task` added (plan's indices stay valid): the plan's
  // routes are kept, the task inserted where it costs least, then a short repair around it.
  FleetPlan insert(const FleetProblem& problem, const FleetPlan& plan, std::size_t task,
                   const StopCondition& stop) const;
  // The routes in `orders` (task indices per robot, in order: a held plan, or each robot's own
  // plan) are kept, and the requests of `tasks` (in no order) go in one after another where each
  // costs least, then `repair_iterations` ruin-and-recreate rounds around each, a round kept only
  // when it improves. A task of `orders` its route can no longer hold (its window, the capacity,
  // the dock) is left out of it, and so is a half of a delivery whose other half is left out; a
  // repair may put it back. Deterministic for the seed and a deterministic `stop`.
  FleetPlan insert(const FleetProblem& problem, const std::vector<std::vector<std::size_t>>& orders,
                   const std::vector<std::size_t>& tasks, const StopCondition& stop) const;

 private:
  FleetSchedulerOptions options_;
};

}  // namespace rondo::schedule
