// Random robot-like days for tests and benchmarks: tasks at the places of a given travel oracle
// (a real map's distance prior in bench/schedule_vs_cbc.cpp), durations of minutes, windows of tens
// of minutes to hours that overlap, priorities; the robot starts at the dock.
//
//   Problem day = robot_day(travel, {.tasks = 15, .seed = 3, .dock = 4});
//
// Contract: deterministic for a given oracle and options; every window leaves room for its task
// (deadline = release + duration + width); a task never sits at the dock when there is any other
// place. Feasibility of the whole day is not promised: the horizon decides how crowded it is.
#pragma once

#include <cstdint>
#include <memory>
#include <random>
#include <string>

#include "rondo/schedule/problem.h"

namespace rondo::schedule::testing {

struct RobotDayOptions {
  std::size_t tasks = 15;
  std::uint64_t seed = 1;
  LocationIndex dock = 0;
  Time start = Time{} + hours(8);    // the robot is free at the dock
  Duration horizon = hours(1);       // releases fall in [start, start + horizon)
  Duration min_duration = minutes(1);
  Duration max_duration = minutes(5);
  Duration min_width = minutes(20);  // window width beyond the duration
  Duration max_width = hours(3);
  int max_priority = 3;              // priorities in 0 .. max_priority
};

inline Problem robot_day(std::shared_ptr<const TravelOracle> travel, const RobotDayOptions& o) {
  std::mt19937_64 rng(o.seed);
  auto uniform = [&](std::int64_t lo, std::int64_t hi) {
    return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng);
  };
  auto uniform_duration = [&](Duration lo, Duration hi) {
    // Whole seconds: people give task durations and windows in seconds, not milliseconds.
    return seconds(uniform(lo.count() / 1000, hi.count() / 1000));
  };
  const auto places = static_cast<std::int64_t>(travel->location_count());
  Problem p;
  p.travel = std::move(travel);
  p.robot.location = o.dock;
  p.robot.time = o.start;
  for (std::size_t i = 0; i < o.tasks; ++i) {
    ProblemTask t;
    t.id = "t" + std::to_string(i);
    auto place = static_cast<LocationIndex>(uniform(0, places - 1));
    if (place == o.dock && places > 1) place = (place + 1) % static_cast<LocationIndex>(places);
    t.start_location = t.end_location = place;
    t.duration = uniform_duration(o.min_duration, o.max_duration);
    t.release = o.start + uniform_duration(Duration{0}, o.horizon - seconds(1));
    t.deadline = t.release + t.duration + uniform_duration(o.min_width, o.max_width);
    t.priority = static_cast<int>(uniform(0, o.max_priority));
    p.tasks.push_back(std::move(t));
  }
  return p;
}

}  // namespace rondo::schedule::testing
