// The robots' anchor, as a baseline only (issue 39, "Against the robots' anchor"): Open-RMF's
// rmf_task greedy allocation. Each task in turn, in order of release, goes to the robot on which
// it finishes earliest, at the end of that robot's queue; travel is static, deadlines are not
// considered. A delivery job is one task there (pickup, then straight to its drop), as an rmf
// delivery request is. Only the robots that run a task's action are candidates (an rmf fleet
// offers a task to the robots that can do it). Written from the description of it, not
// from rmf_task's code.
//
//   std::vector<std::vector<std::size_t>> orders = rmf_greedy_orders(problem);
//   Result<FleetPlan> plan = time_fleet_routes(problem, orders);   // then check_fleet_plan
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <optional>
#include <vector>

#include "rondo/schedule/fleet_problem.h"

namespace rondo::bench {

// The orders rmf's greedy gives: one task list per robot. Precondition: validate_fleet(problem);
// a pickup's drop is the only task naming its job as a drop, and no task is `after` another.
inline std::vector<std::vector<std::size_t>> rmf_greedy_orders(const schedule::FleetProblem& problem) {
  using schedule::ItemAction;
  const std::size_t n = problem.tasks.size();
  // A unit: a task, or a pickup with its drop.
  std::vector<std::vector<std::size_t>> units;
  std::vector<bool> in_unit(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& transfer = problem.tasks[i].task.transfer;
    if (in_unit[i] || (transfer && transfer->action == ItemAction::kDrop)) continue;
    std::vector<std::size_t> unit{i};
    if (transfer)
      for (std::size_t j = 0; j < n; ++j) {
        const auto& other = problem.tasks[j].task.transfer;
        if (other && other->action == ItemAction::kDrop && other->job == transfer->job) unit.push_back(j);
      }
    for (std::size_t k : unit) in_unit[k] = true;
    units.push_back(std::move(unit));
  }
  std::stable_sort(units.begin(), units.end(), [&](const auto& a, const auto& b) {
    return problem.tasks[a.front()].task.release < problem.tasks[b.front()].task.release;
  });
  struct RobotState {
    schedule::LocationIndex at;
    Time free;
  };
  std::vector<RobotState> state;
  for (const schedule::FleetRobot& r : problem.robots) state.push_back({r.location, r.free_from});
  const auto can_run = [&](std::size_t robot, std::size_t task) {
    const schedule::FleetTask& f = problem.tasks[task];
    if (f.pinned_robot) return *f.pinned_robot == robot;
    const auto& actions = problem.robots[robot].actions;
    return f.action.empty() || std::find(actions.begin(), actions.end(), f.action) != actions.end();
  };
  // Where and when the robot is once it has done the unit, appended to its queue.
  const auto after_unit = [&](std::size_t robot, const std::vector<std::size_t>& unit) {
    RobotState s = state[robot];
    for (std::size_t k : unit) {
      const schedule::ProblemTask& t = problem.tasks[k].task;
      const Time start =
          std::max(s.free + schedule::robot_travel(problem, robot, s.at, t.start_location, s.free), t.release);
      s.free = start + t.duration;  // the duration takes it to its end place, as the checker times it
      s.at = t.end_location;
    }
    return s;
  };
  std::vector<std::vector<std::size_t>> orders(problem.robots.size());
  for (const auto& unit : units) {
    std::optional<std::size_t> best;
    RobotState best_state{};
    for (std::size_t r = 0; r < problem.robots.size(); ++r) {
      if (!std::all_of(unit.begin(), unit.end(), [&](std::size_t k) { return can_run(r, k); })) continue;
      const RobotState s = after_unit(r, unit);
      if (!best || s.free < best_state.free) best = r, best_state = s;
    }
    if (!best) continue;  // no robot runs it: left out
    state[*best] = best_state;
    orders[*best].insert(orders[*best].end(), unit.begin(), unit.end());
  }
  return orders;
}

}  // namespace rondo::bench
