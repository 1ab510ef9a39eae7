// Time from an observation that breaks an assumption to the new schedule (issue 16; the goal is
// under 20 ms), and from a door seen open to the opportunity's decision (the check that every
// planned task still fits, the scheduler run on the alternative). On the office example's map
// (examples/office/map.yaml, run from the project root), the executor on the scripted robot
// (tests/exec/scripted_robot.h) with `jobs` courier jobs queued at 08:00 (pickup and drop at
// random desks, deadlines 10:00-12:00; each the pair of a job, so 2 x jobs tasks) and the hallway
// patrol: a door that a planned task needs is seen closed (the tasks behind it are blocked, the
// rest rescheduled at once), then seen open (the opportunity checked and taken or declined).
// Wall time on the steady clock per observation, everything the executor does before the clock is
// idle again (store writes included; the store is a temporary SQLite file, commits unsynced).
//
//   cmake --build build --target bench_courier && build/bench/bench_courier [reps] [jobs]  # 200 8
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "exec/scripted_executor.h"
#include "rondo/map/map_loader.h"

namespace {

using namespace rondo;
using namespace rondo::exec;

using rondo::bench::quantile;

Task half(const std::string& job, DeliveryRole role, const std::string& node, Time release, Time deadline) {
  Task t;
  t.id = job + (role == DeliveryRole::kPickup ? "-pickup" : "-drop");
  t.activity = t.id;
  t.window = TimeWindow{release, deadline};
  t.duration = minutes(1);
  t.priority = 4;
  t.start_node = node;
  t.actions = {Action{.name = role == DeliveryRole::kPickup ? "load" : "unload", .args = {}}};
  t.delivery = Delivery{.job = job, .role = role, .object = "parcel " + job, .appearance = "", .load = 1};
  if (role == DeliveryRole::kDrop) t.after = {job + "-pickup"};
  return t;
}

}  // namespace

int main(int argc, char** argv) {
  const int reps = argc > 1 ? std::atoi(argv[1]) : 200;
  const int jobs = argc > 2 ? std::atoi(argv[2]) : 8;
  auto map = map::load_map("examples/office/map.yaml");
  if (!map) {
    fmt::print(stderr, "bench_courier: {} (run from the project root)\n", map.error().message);
    return 2;
  }
  const std::vector<std::string> desks{"A-110-Desk", "A-111-Table", "A-114-Desk", "A-120-Desk", "A-123-Desk"};
  std::vector<double> broken, opened;
  int taken = 0, declined = 0, no_break = 0;
  std::mt19937_64 rng(1);
  for (int rep = 0; rep < reps; ++rep) {
    exec::testing::ScriptedExecutor s({}, *map, {}, "ChargingPoint");
    std::vector<Task> tasks;
    std::uniform_int_distribution<std::size_t> pick(0, desks.size() - 1);
    std::uniform_int_distribution<int> until(120, 240);
    for (int j = 0; j < jobs; ++j) {
      const std::string from = desks[pick(rng)];
      std::string to = desks[pick(rng)];
      while (to == from) to = desks[pick(rng)];
      const Time deadline = s.at("08:00") + minutes(until(rng));
      tasks.push_back(half(fmt::format("job{}", j), DeliveryRole::kPickup, from, s.at("08:00"), deadline));
      tasks.push_back(half(fmt::format("job{}", j), DeliveryRole::kDrop, to, s.at("08:00"), deadline));
    }
    if (!s.fleet().add_tasks(tasks, "bench").ok()) return 1;
    s.fleet().start();
    s.settle();
    // A door the plan needs, of a task after the first (the first one runs: its door is checked too).
    std::vector<std::string> doors;
    for (const Assumption& a : s.executor().assumptions())
      if (a.kind == Assumption::Kind::kDoorOpen) doors.push_back(a.what);
    if (doors.empty()) {
      ++no_break;
      continue;
    }
    const std::string door = doors[std::uniform_int_distribution<std::size_t>(0, doors.size() - 1)(rng)];
    const int before = s.executor().assumption_stats().broken;
    double t0 = bench::steady_seconds();
    s.robot().observe("door_open", door, 0);
    s.settle();
    broken.push_back(bench::steady_seconds() - t0);
    if (s.executor().assumption_stats().broken == before) ++no_break;
    s.run_until("08:01");
    t0 = bench::steady_seconds();
    s.robot().observe("door_open", door, 1);
    s.settle();
    opened.push_back(bench::steady_seconds() - t0);
    taken += s.executor().assumption_stats().opportunities_taken;
    declined += s.executor().assumption_stats().opportunities_declined;
  }
  fmt::print("bench_courier: {} reps, {} jobs ({} tasks) each; load average {}\n", reps, jobs, 2 * jobs,
             bench::load_average());
  fmt::print("  door seen closed -> new schedule: median {:.2f} ms, p99 {:.2f} ms, max {:.2f} ms (n = {})\n",
             1e3 * quantile(broken, 0.5), 1e3 * quantile(broken, 0.99), 1e3 * quantile(broken, 1.0), broken.size());
  fmt::print("  door seen open -> opportunity decided: median {:.2f} ms, p99 {:.2f} ms (n = {}; {} taken, {} "
             "declined)\n",
             1e3 * quantile(opened, 0.5), 1e3 * quantile(opened, 0.99), opened.size(), taken, declined);
  if (no_break > 0) fmt::print("  {} reps broke nothing (no planned task behind the door)\n", no_break);
  return 0;
}
