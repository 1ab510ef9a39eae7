// The fleet scheduling problem (issue 39): several robots, each with its own start, time, dock,
// actions, capacity, speed and travel; tasks as in the one-robot Problem (windows, durations,
// priorities, deliveries, `after` links) plus the action they need and an optional pinned robot.
//
//   FleetProblem f;
//   f.travel = std::make_shared<MatrixTravel>(...);           // shared by robots without their own
//   f.robots.push_back({.name = "r1", .location = 0, .free_from = t0, .capacity = 2});
//   f.tasks.push_back({.task = {.id = "check", .release = t0, .deadline = t0 + minutes(30), ...}});
//   if (auto ok = validate_fleet(f); !ok) ...;
//
// Rules (docs/scheduling.md, "The fleet problem"): every robot runs its tasks one after another as
// a one-robot Problem does; a pickup and its drop go on the same robot, the pickup first; tasks
// joined by `after` (in either direction) go on the same robot, in order; a pinned task only on
// its robot; a task that names an action only on a robot that lists it. A task that cannot be
// planned is dropped, at a cost that grows with its priority.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/schedule/problem.h"
#include "rondo/schedule/travel_oracle.h"

namespace rondo::schedule {

struct FleetRobot {
  std::string name{};
  LocationIndex location = 0;
  Time free_from{};
  std::optional<ReturnTo> end{};      // its dock, reached by the deadline after its last task
  std::vector<std::string> actions{};  // what it can run; a task with no action runs anywhere
  std::int64_t capacity = 0;           // 0 = unlimited
  double speed_factor = 1.0;           // travel takes oracle time / speed_factor
  std::shared_ptr<const TravelOracle> travel{};  // null: FleetProblem::travel
};

struct FleetTask {
  ProblemTask task{};                      // `after` holds indices into FleetProblem::tasks
  std::string action{};                    // "" = any robot
  std::optional<std::size_t> pinned_robot{};  // index into FleetProblem::robots
  std::optional<Time> due{};               // soft: lateness past it is charged (kSumOfEnds)
  // Load taken on here and kept to the end of the route: the routing benchmarks' customer demand
  // (VRPTW). Counts against the capacity like an item on board.
  std::int64_t demand = 0;
};

enum class FleetObjective {
  // The paper's sum of end times (each from its robot's free_from), plus lateness past `due` and
  // drops, both weighted by priority (FleetCosts).
  kSumOfEnds,
  // The routing benchmarks' objective: fewest robots used, then least total distance.
  kVehiclesThenDistance,
};

// Weights of the soft terms, in seconds of the objective.
struct FleetCosts {
  double lateness_per_second = 1.0;  // times (1 + priority)
  double drop_seconds = 1e7;         // times (1 + priority); far above any plan's sum of ends
};

struct FleetProblem {
  std::vector<FleetRobot> robots{};
  std::vector<FleetTask> tasks{};
  std::shared_ptr<const TravelOracle> travel{};
  // Distance between locations for kVehiclesThenDistance (row-major, location_count squared).
  // Empty: the travel oracle's lower bound, in seconds.
  std::vector<double> distance{};
  FleetObjective objective = FleetObjective::kSumOfEnds;
  FleetCosts costs{};

  const TravelOracle& travel_of(std::size_t robot) const {
    return robots[robot].travel ? *robots[robot].travel : *travel;
  }
  double distance_between(LocationIndex from, LocationIndex to) const;
};

// Structural checks with the task or robot named: an oracle for every robot, locations in range,
// durations >= 0, windows not empty, speed factors > 0, pins in range, `after` valid and acyclic,
// every drop with exactly one pickup (robots start empty), no job picked up twice, a distance
// matrix of the right size when given.
Status validate_fleet(const FleetProblem& problem);

// Travel of one robot: its oracle, divided by its speed factor (rounded up to the millisecond).
Duration robot_travel(const FleetProblem& problem, std::size_t robot, LocationIndex from, LocationIndex to,
                      Time depart);

}  // namespace rondo::schedule
