// The default scheduler against the paper's MIP on CBC, in the same run (issue 5), on the real G4S
// map (../shared/data/maps/g4s_y2.tmap) with travel = its distance prior (all-pairs expected
// seconds from plan::TravelPlanner over plan::DistancePrior, i.e. shortest nominal travel times):
// 1. 30 random robot-like days of 15 tasks (tests/schedule/robot_day.h: durations of 1-5 min,
//    releases within an hour, windows 20 min - 3 h wide, so they overlap): CBC (full and
//    interval-algebra model) with 10 s each, the default scheduler run to its proof; objective and
//    time of each (default: median of 3 runs; CBC: --cbc-runs, 1 by default), and the time ratio;
// 2. days of 50, 100, 200 and 500 tasks: each solver with a 10 s budget, the default also with 2 s
//    and alone with its first schedule (median of 3 for that one; budgeted runs take their budget).
//
//   build-sched/bench/bench_schedule_vs_cbc [--quick] [--days-only | --scale-only] [--map FILE] [--cbc-runs N]
// Run from the project root. Prints the machine's load average before and after (shared machine).
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench_clock.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/schedule/mip_scheduler.h"
#include "schedule/robot_day.h"
#include "schedule_map_travel.h"

namespace {

using rondo::bench::load_average;
using rondo::bench::steady_seconds;

using namespace rondo;
using namespace rondo::schedule;

using bench::MapMatrix;

struct Run {
  Schedule schedule;
  double seconds = 0;
  bool checked = false;
};

Run run(Scheduler& solver, const Problem& p, double budget) {
  const double started = steady_seconds();
  const DeadlineStop stop(steady_seconds, started + budget);
  Run r;
  r.schedule = solver.solve(p, stop);
  r.seconds = steady_seconds() - started;
  r.checked = check_schedule(p, r.schedule).ok();
  return r;
}

// The median-time run of `count` (the answers agree: every solver here is deterministic).
Run median_run(Scheduler& solver, const Problem& p, double budget, int count) {
  std::vector<Run> runs;
  for (int r = 0; r < count; ++r) runs.push_back(run(solver, p, budget));
  std::sort(runs.begin(), runs.end(), [](const Run& x, const Run& y) { return x.seconds < y.seconds; });
  return runs[runs.size() / 2];
}

bool complete(const Schedule& s) { return s.status == SolveStatus::kOptimal || s.status == SolveStatus::kFeasible; }

std::string objective(const Run& r) {
  if (!complete(r.schedule)) return std::string(to_string(r.schedule.status));
  return fmt::format("{:.0f}{}{}", to_seconds(r.schedule.objective), r.schedule.status == SolveStatus::kOptimal ? "*" : "",
                     r.checked ? "" : "!");
}

testing::RobotDayOptions day(const MapMatrix& m, std::size_t tasks, std::uint64_t seed) {
  testing::RobotDayOptions o;
  o.tasks = tasks;
  o.seed = seed;
  o.dock = m.dock;
  // 15 tasks: releases within the first hour. Longer days: a task every 3 minutes on average, so
  // 500 tasks span 25 hours of releases (the robot is busy about 80 % of that time).
  o.horizon = tasks <= 20 ? hours(1) : minutes(3) * static_cast<std::int64_t>(tasks);
  o.min_duration = minutes(1);
  o.max_duration = tasks <= 20 ? minutes(5) : minutes(3);
  return o;
}

void print_map(const MapMatrix& m) {
  double lo = 1e18, hi = 0, sum = 0;
  std::size_t count = 0;
  for (LocationIndex a = 0; a < m.names.size(); ++a)
    for (LocationIndex b = 0; b < m.names.size(); ++b)
      if (a != b) {
        const double s = to_seconds(m.travel->at(a, b));
        lo = std::min(lo, s), hi = std::max(hi, s), sum += s, ++count;
      }
  std::cout << fmt::format("# map g4s_y2: {} places, dock {}, travel between places {:.1f} .. {:.1f} s (mean {:.1f})\n",
                           m.names.size(), m.names[m.dock], lo, hi, sum / static_cast<double>(count));
}

void compare_small_days(const MapMatrix& m, int instances, double cbc_budget, int cbc_runs) {
  std::cout << "# 15-task days: CBC (" << cbc_budget
            << " s, median of " << cbc_runs
            << " runs) vs the default scheduler (run to its proof, median of 3 runs); * = proved optimal\n";
  std::cout << fmt::format("{:>4} {:>10} {:>8} {:>10} {:>8} {:>10} {:>8} {:>8} {:>8}\n", "seed", "mip", "mip s",
                           "mip-ia", "mip-ia s", "default", "def s", "ratio", "ratio-ia");
  int no_worse = 0, fast = 0, cbc_found = 0;
  std::vector<double> ratios;
  for (int k = 1; k <= instances; ++k) {
    const Problem p = testing::robot_day(m.travel, day(m, 15, static_cast<std::uint64_t>(k)));
    MipScheduler mip(MipOptions{false, from_seconds(cbc_budget)});
    MipScheduler mip_ia(MipOptions{true, from_seconds(cbc_budget)});
    DefaultScheduler ours;
    const Run a = median_run(mip, p, cbc_budget, cbc_runs);
    const Run b = median_run(mip_ia, p, cbc_budget, cbc_runs);
    const Run c = median_run(ours, p, cbc_budget, 3);
    const double ratio = a.seconds / std::max(c.seconds, 1e-6);
    const double ratio_ia = b.seconds / std::max(c.seconds, 1e-6);
    auto no_worse_than = [&](const Run& cbc) {
      return complete(c.schedule) && (!complete(cbc.schedule) || c.schedule.objective <= cbc.schedule.objective);
    };
    no_worse += no_worse_than(a) && no_worse_than(b);
    fast += std::min(ratio, ratio_ia) >= 100;
    ratios.push_back(std::min(ratio, ratio_ia));
    cbc_found += complete(a.schedule) || complete(b.schedule);
    std::cout << fmt::format("{:>4} {:>10} {:>8.3f} {:>10} {:>8.3f} {:>10} {:>8.5f} {:>7.0f}x {:>7.0f}x\n", k,
                             objective(a), a.seconds, objective(b), b.seconds, objective(c), c.seconds, ratio, ratio_ia)
              << std::flush;
  }
  std::sort(ratios.begin(), ratios.end());
  std::cout << fmt::format(
      "default no worse than either CBC model: {}/{}; at least 100x faster than the faster CBC model: {}/{}; "
      "ratio min {:.0f}x, median {:.0f}x; CBC found a schedule on {}\n\n",
      no_worse, instances, fast, instances, ratios.front(), ratios[ratios.size() / 2], cbc_found);
}

void compare_scale(const MapMatrix& m, bool quick) {
  const double budget = quick ? 3.0 : 10.0;
  std::cout << "# scale: objective (s) and seconds; 10 s budget each (default also with 2 s); `first` = the\n"
               "# default scheduler's first schedule (the first restricted dynamic program alone), median of 3\n";
  std::cout << fmt::format("{:>5} {:>12} {:>6} {:>12} {:>6} {:>12} {:>6} {:>12} {:>6} {:>12} {:>6}\n", "tasks",
                           "first", "s", "default 2s", "s", "default 10s", "s", "mip", "s", "mip-ia", "s");
  const std::vector<std::size_t> sizes =
      quick ? std::vector<std::size_t>{50, 100} : std::vector<std::size_t>{50, 100, 200, 500};
  for (std::size_t n : sizes) {
    const Problem p = testing::robot_day(m.travel, day(m, n, 1000 + n));
    DefaultSchedulerOptions construct_only;
    construct_only.improve = false;    // no local search after the first restricted program
    construct_only.exact_max_tasks = 0;  // and no exact program: the first schedule alone
    DefaultScheduler first(construct_only);
    const Run d0 = median_run(first, p, 2.0, 3);
    DefaultScheduler ours;
    const Run d2 = run(ours, p, 2.0);
    const Run d10 = run(ours, p, budget);
    MipScheduler mip(MipOptions{false, from_seconds(budget)});
    MipScheduler mip_ia(MipOptions{true, from_seconds(budget)});
    const Run a = run(mip, p, budget);
    const Run b = run(mip_ia, p, budget);
    std::cout << fmt::format("{:>5} {:>12} {:>6.2f} {:>12} {:>6.2f} {:>12} {:>6.2f} {:>12} {:>6.2f} {:>12} {:>6.2f}\n",
                             n, objective(d0), d0.seconds, objective(d2), d2.seconds, objective(d10), d10.seconds,
                             objective(a), a.seconds, objective(b), b.seconds)
              << std::flush;
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, days = true, scale = true;
  int cbc_runs = 1;  // CBC takes seconds here, so one run: its time is far beyond any noise
  std::string map_file = "../shared/data/maps/g4s_y2.tmap";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    else if (std::strcmp(argv[i], "--days-only") == 0) scale = false;
    else if (std::strcmp(argv[i], "--scale-only") == 0) days = false;
    else if (std::strcmp(argv[i], "--map") == 0 && i + 1 < argc) map_file = argv[++i];
    else if (std::strcmp(argv[i], "--cbc-runs") == 0 && i + 1 < argc) cbc_runs = std::max(1, std::atoi(argv[++i]));
    else {
      std::cerr << "usage: bench_schedule_vs_cbc [--quick] [--days-only | --scale-only] [--map FILE] [--cbc-runs N]\n";
      return 2;
    }
  }
  auto m = bench::map_travel(map_file, "ChargingPoint", Time{} + hours(8));
  if (!m) {
    std::cerr << m.error().message << '\n';
    return 1;
  }
  std::cout << "# load average before: " << load_average() << '\n';
  print_map(*m);
  if (days) compare_small_days(*m, quick ? 5 : 30, quick ? 2.0 : 10.0, cbc_runs);
  if (scale) compare_scale(*m, quick);
  std::cout << "# load average after: " << load_average() << '\n';
  return 0;
}
