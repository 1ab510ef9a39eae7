// The fleet scheduler at the fleet's size (issue 39): robot-like days of 1,000 tasks and 100
// robots (a 200 x 200 m grid, 1 m/s, releases over 10 h, windows 20 min - 3 h, durations up to
// 2 min): the time to the first feasible plan, then inserting one new task into the solved plan,
// p50 / p99 / max over many new tasks (each into the same solved plan), with the default repair.
//
//   build/bench/bench_fleet_scale [days=3] [inserts=200] [solve_seconds=5]
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "bench_clock.h"
#include "random_fleet.h"
#include "rondo/schedule/fleet_checker.h"
#include "rondo/schedule/fleet_scheduler.h"

using rondo::bench::steady_seconds;
using namespace rondo::schedule;

namespace {

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const auto at = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1) + 0.5);
  return v[std::min(at, v.size() - 1)];
}

}  // namespace

int main(int argc, char** argv) {
  const int days = argc > 1 ? std::atoi(argv[1]) : 3;
  const int inserts = argc > 2 ? std::atoi(argv[2]) : 200;
  const double solve_seconds = argc > 3 ? std::atof(argv[3]) : 5.0;
  std::printf("load average before: %s\n", rondo::bench::load_average().c_str());
  // Insertion times twice: wall (what a caller waits on a quiet machine) and the thread's CPU time
  // (what it costs, whatever else the machine runs).
  std::printf("%4s %10s %8s %10s %10s %8s %10s %10s %10s %10s %10s %8s\n", "day", "first s", "planned", "objective",
              "solved obj", "planned", "ins p50 ms", "ins p99 ms", "ins max ms", "cpu p50 ms", "cpu p99 ms", "checked");
  for (int day = 1; day <= days; ++day) {
    FleetProblem p = testing::random_fleet({.robots = 100, .tasks = 1000, .seed = static_cast<std::uint64_t>(day),
                                            .horizon_s = 36000, .min_width_s = 1200, .max_width_s = 10800, .grid = 200});
    // The first plan: construction only, timed alone.
    double started = steady_seconds();
    const FleetPlan first = FleetScheduler({.seed = 1, .improve = false}).solve(p, NeverStop{});
    const double first_s = steady_seconds() - started;
    started = steady_seconds();
    const DeadlineStop stop(steady_seconds, started + solve_seconds);
    const FleetPlan solved = FleetScheduler({.seed = 1}).solve(p, stop);
    bool checked = check_fleet_plan(p, first).ok() && check_fleet_plan(p, solved).ok();
    // New tasks, one at a time, each into the solved plan.
    std::mt19937_64 rng(static_cast<std::uint64_t>(day) * 7919);
    std::vector<double> ms, cpu_ms;
    const FleetProblem base = p;
    for (int k = 0; k < inserts; ++k) {
      FleetProblem q = base;
      FleetTask t = base.tasks[std::uniform_int_distribution<std::size_t>(0, base.tasks.size() - 1)(rng)];
      t.task.id = "new" + std::to_string(k);
      t.task.start_location = t.task.end_location = std::uniform_int_distribution<std::size_t>(0, 999)(rng);
      q.tasks.push_back(t);
      const double t0 = steady_seconds(), c0 = rondo::bench::thread_seconds();
      const FleetPlan after = FleetScheduler({.seed = 1}).insert(q, solved, q.tasks.size() - 1, NeverStop{});
      cpu_ms.push_back(1000.0 * (rondo::bench::thread_seconds() - c0));
      ms.push_back(1000.0 * (steady_seconds() - t0));
      if (k < 10) checked = checked && check_fleet_plan(q, after).ok();
    }
    std::printf("%4d %10.3f %8zu %10.0f %10.0f %8zu %10.2f %10.2f %10.2f %10.2f %10.2f %8s\n", day, first_s,
                first.planned(), first.objective, solved.objective, solved.planned(), percentile(ms, 0.5),
                percentile(ms, 0.99), *std::max_element(ms.begin(), ms.end()), percentile(cpu_ms, 0.5),
                percentile(cpu_ms, 0.99), checked ? "yes" : "NO");
    std::fflush(stdout);
  }
  std::printf("load average after: %s\n", rondo::bench::load_average().c_str());
  return 0;
}
