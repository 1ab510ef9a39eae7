// Random robot-like scheduling problems for tests and benchmarks: places on a grid with Manhattan
// travel (so the triangle inequality holds and the paper's pairwise MIP is exact), tasks with
// overlapping windows, optional deliveries (pickup/drop pairs, capacity, same-looking items).
//
//   Problem p = random_problem({.tasks = 10, .seed = 3});
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "rondo/schedule/problem.h"

namespace rondo::schedule::testing {

struct RandomProblemOptions {
  std::size_t tasks = 10;
  std::uint64_t seed = 1;
  std::int64_t horizon_s = 3600;      // releases fall in [0, horizon)
  std::int64_t min_width_s = 600;     // window widths (end deadline minus release)
  std::int64_t max_width_s = 2400;
  std::int64_t max_duration_s = 120;
  std::int64_t grid = 60;             // places on a grid; one step = 1 s of travel at 1 m/s
  std::size_t deliveries = 0;         // pickup/drop pairs among the tasks
  std::int64_t capacity = 0;
  bool same_looking = false;          // deliveries share two appearances
  bool precedence = false;            // a few random `after` edges (forward in index order)
};

inline Problem random_problem(const RandomProblemOptions& o) {
  std::mt19937_64 rng(o.seed);
  auto uniform = [&](std::int64_t lo, std::int64_t hi) {
    return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng);
  };
  const std::size_t places = o.tasks + 1;
  std::vector<std::pair<std::int64_t, std::int64_t>> xy(places);
  for (auto& p : xy) p = {uniform(0, o.grid), uniform(0, o.grid)};
  std::vector<Duration> m(places * places);
  for (std::size_t a = 0; a < places; ++a)
    for (std::size_t b = 0; b < places; ++b)
      m[a * places + b] = seconds(std::abs(xy[a].first - xy[b].first) + std::abs(xy[a].second - xy[b].second));
  Problem p;
  p.travel = std::make_shared<MatrixTravel>(MatrixTravel::create(places, std::move(m)).value());
  p.robot.location = 0;
  p.robot.time = Time{} + hours(8);
  p.robot.capacity = o.capacity;
  for (std::size_t i = 0; i < o.tasks; ++i) {
    ProblemTask t;
    t.id = "t" + std::to_string(i);
    t.duration = seconds(uniform(0, o.max_duration_s));
    t.release = p.robot.time + seconds(uniform(0, o.horizon_s));
    t.deadline = t.release + t.duration + seconds(uniform(o.min_width_s, o.max_width_s));
    t.priority = static_cast<int>(uniform(0, 3));
    t.start_location = i + 1;
    t.end_location = uniform(0, 3) == 0 ? static_cast<std::size_t>(uniform(1, static_cast<std::int64_t>(o.tasks))) : i + 1;
    p.tasks.push_back(std::move(t));
  }
  for (std::size_t d = 0; d < o.deliveries && 2 * d + 1 < o.tasks; ++d) {
    const std::string job = "job" + std::to_string(d);
    const std::string look = o.same_looking ? (d % 2 == 0 ? "red folder" : "blue box") : "";
    p.tasks[2 * d].transfer = ItemTransfer{job, ItemAction::kPickup, look, 1};
    p.tasks[2 * d + 1].transfer = ItemTransfer{job, ItemAction::kDrop, look, 1};
    // Leave room for the pickup first.
    if (p.tasks[2 * d + 1].deadline < p.tasks[2 * d].release + hours(1))
      p.tasks[2 * d + 1].deadline = p.tasks[2 * d].release + hours(1);
  }
  if (o.precedence && o.tasks >= 4) {
    for (int e = 0; e < 2; ++e) {
      const auto a = static_cast<std::size_t>(uniform(0, static_cast<std::int64_t>(o.tasks) - 2));
      const auto b = static_cast<std::size_t>(uniform(static_cast<std::int64_t>(a) + 1, static_cast<std::int64_t>(o.tasks) - 1));
      p.tasks[b].after.push_back(a);
    }
  }
  return p;
}

}  // namespace rondo::schedule::testing
