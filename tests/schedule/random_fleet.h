// Random fleet problems for tests: places on a grid with Manhattan travel, robots at random
// places and times (some with a dock, a capacity, actions, a speed factor), tasks with windows,
// optional deliveries (same-looking items too), pins, actions and `after` links.
//
//   FleetProblem f = random_fleet({.robots = 3, .tasks = 12, .seed = 5, .deliveries = 2});
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "rondo/schedule/fleet_problem.h"

namespace rondo::schedule::testing {

struct RandomFleetOptions {
  std::size_t robots = 3;
  std::size_t tasks = 10;
  std::uint64_t seed = 1;
  std::int64_t horizon_s = 3600;
  std::int64_t min_width_s = 300;
  std::int64_t max_width_s = 2400;
  std::int64_t grid = 60;
  std::size_t deliveries = 0;
  std::int64_t capacity = 0;
  bool same_looking = false;
  bool pins = false;
  bool actions = false;
  bool precedence = false;
  bool docks = false;
  bool speeds = false;
  FleetObjective objective = FleetObjective::kSumOfEnds;
};

inline FleetProblem random_fleet(const RandomFleetOptions& o) {
  std::mt19937_64 rng(o.seed);
  auto uniform = [&](std::int64_t lo, std::int64_t hi) { return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng); };
  const std::size_t places = o.tasks + o.robots;
  std::vector<std::pair<std::int64_t, std::int64_t>> xy(places);
  for (auto& p : xy) p = {uniform(0, o.grid), uniform(0, o.grid)};
  std::vector<Duration> m(places * places);
  FleetProblem f;
  f.distance.resize(places * places);
  for (std::size_t a = 0; a < places; ++a)
    for (std::size_t b = 0; b < places; ++b) {
      const std::int64_t d = std::abs(xy[a].first - xy[b].first) + std::abs(xy[a].second - xy[b].second);
      m[a * places + b] = seconds(d);
      f.distance[a * places + b] = static_cast<double>(d);
    }
  f.travel = std::make_shared<MatrixTravel>(MatrixTravel::create(places, std::move(m)).value());
  f.objective = o.objective;
  const Time t0 = Time{} + hours(8);
  for (std::size_t r = 0; r < o.robots; ++r) {
    FleetRobot robot{.name = "r" + std::to_string(r), .location = o.tasks + r, .free_from = t0 + seconds(uniform(0, 300)),
                     .capacity = o.capacity};
    if (o.docks) robot.end = ReturnTo{o.tasks + r, t0 + seconds(o.horizon_s + o.max_width_s + 3600)};
    if (o.actions) robot.actions = r % 2 == 0 ? std::vector<std::string>{"clean"} : std::vector<std::string>{"clean", "open"};
    if (o.speeds) robot.speed_factor = r % 2 == 0 ? 1.0 : 1.5;
    f.robots.push_back(std::move(robot));
  }
  for (std::size_t i = 0; i < o.tasks; ++i) {
    FleetTask t;
    t.task.id = "t" + std::to_string(i);
    t.task.duration = seconds(uniform(0, 120));
    t.task.release = t0 + seconds(uniform(0, o.horizon_s));
    t.task.deadline = t.task.release + t.task.duration + seconds(uniform(o.min_width_s, o.max_width_s));
    t.task.priority = static_cast<int>(uniform(0, 3));
    t.task.start_location = t.task.end_location = i;
    if (o.pins && uniform(0, 5) == 0) t.pinned_robot = static_cast<std::size_t>(uniform(0, static_cast<std::int64_t>(o.robots) - 1));
    if (o.actions && uniform(0, 4) == 0) t.action = uniform(0, 1) == 0 ? "clean" : "open";
    f.tasks.push_back(std::move(t));
  }
  for (std::size_t d = 0; d < o.deliveries && 2 * d + 1 < o.tasks; ++d) {
    const std::string job = "job" + std::to_string(d);
    const std::string look = o.same_looking ? (d % 2 == 0 ? "red folder" : "blue box") : "";
    f.tasks[2 * d].task.transfer = ItemTransfer{.job = job, .action = ItemAction::kPickup, .appearance = look};
    f.tasks[2 * d + 1].task.transfer = ItemTransfer{.job = job, .action = ItemAction::kDrop, .appearance = look};
    f.tasks[2 * d + 1].task.release = std::min(f.tasks[2 * d + 1].task.release, f.tasks[2 * d].task.release + minutes(5));
    f.tasks[2 * d + 1].task.deadline = std::max(f.tasks[2 * d + 1].task.deadline, f.tasks[2 * d].task.deadline + minutes(30));
  }
  if (o.precedence)
    for (std::size_t i = 2 * o.deliveries + 1; i < o.tasks; ++i)
      if (uniform(0, 3) == 0) f.tasks[i].task.after.push_back(i - 1);
  return f;
}

}  // namespace rondo::schedule::testing
