// Which poll budget (PollBudgetStop) should the executor give the default scheduler? On robot-like
// days of 10-40 tasks on the real G4S map (distance prior), for each budget: the median and the
// largest solve time (each the median of 3 runs), the mean and largest gap to the best schedule
// found with a 1 s budget, and how many instances reached it or were proved optimal.
//
//   build-sched/bench/bench_schedule_poll_budget [--instances N]
// Run from the project root. Prints the load average before and after (shared machine).
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench_clock.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "schedule/robot_day.h"
#include "schedule_map_travel.h"

namespace {

using rondo::bench::load_average;
using rondo::bench::steady_seconds;

using namespace rondo;
using namespace rondo::schedule;

bool complete(const Schedule& s) { return s.status == SolveStatus::kOptimal || s.status == SolveStatus::kFeasible; }

struct Timed {
  Schedule schedule;
  double seconds = 0;
};

Timed median_of_3(const Problem& p, std::int64_t polls) {
  std::vector<Timed> runs;
  for (int r = 0; r < 3; ++r) {
    const PollBudgetStop stop(polls);
    const double started = steady_seconds();
    Timed t{DefaultScheduler{}.solve(p, stop), 0};
    t.seconds = steady_seconds() - started;
    runs.push_back(std::move(t));
  }
  std::sort(runs.begin(), runs.end(), [](const Timed& a, const Timed& b) { return a.seconds < b.seconds; });
  return runs[1];
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1) + 0.5)];
}

}  // namespace

int main(int argc, char** argv) {
  int instances = 20;
  if (argc == 3 && std::strcmp(argv[1], "--instances") == 0) instances = std::atoi(argv[2]);
  auto g4s = bench::map_travel("../shared/data/maps/g4s_y2.tmap", "ChargingPoint", Time{} + hours(8));
  if (!g4s) {
    std::cerr << g4s.error().message << '\n';
    return 1;
  }
  std::cout << "# load average before: " << load_average() << '\n';
  const std::vector<std::int64_t> budgets = {300, 1000, 2000, 5000, 10000, 30000};
  std::cout << fmt::format("{:>5} {:>8} {:>9} {:>9} {:>9} {:>10} {:>9} {:>8} {:>7} {:>6}\n", "tasks", "polls",
                           "median ms", "p90 ms", "max ms", "mean gap %", "max gap %", "at best", "proved", "found");
  for (std::size_t n : {10UL, 15UL, 20UL, 30UL, 40UL}) {
    std::vector<Problem> days;
    std::vector<Duration> best;
    for (int k = 1; k <= instances; ++k) {
      testing::RobotDayOptions o;
      o.tasks = n;
      o.seed = static_cast<std::uint64_t>(100 * n + static_cast<std::size_t>(k));
      o.dock = g4s->dock;
      o.horizon = minutes(4) * static_cast<std::int64_t>(n);  // a task every 4 minutes on average
      days.push_back(testing::robot_day(g4s->travel, o));
      const double started = steady_seconds();
      const DeadlineStop one_second(steady_seconds, started + 1.0);
      const Schedule ref = DefaultScheduler{}.solve(days.back(), one_second);
      best.push_back(complete(ref) ? ref.objective : Duration{-1});
    }
    for (std::int64_t polls : budgets) {
      std::vector<double> ms, gaps;
      int at_best = 0, proved = 0, found = 0;
      for (std::size_t k = 0; k < days.size(); ++k) {
        const Timed t = median_of_3(days[k], polls);
        ms.push_back(t.seconds * 1000);
        if (!complete(t.schedule) || best[k] < Duration{0}) continue;
        if (!check_schedule(days[k], t.schedule).ok()) std::cerr << "checker refused a schedule!\n";
        ++found;
        proved += t.schedule.status == SolveStatus::kOptimal;
        const double gap = 100.0 * (to_seconds(t.schedule.objective) - to_seconds(best[k])) / to_seconds(best[k]);
        gaps.push_back(gap);
        at_best += t.schedule.objective <= best[k];
      }
      const double mean_gap = gaps.empty() ? 0 : [&] {
        double s = 0;
        for (double g : gaps) s += g;
        return s / static_cast<double>(gaps.size());
      }();
      std::cout << fmt::format("{:>5} {:>8} {:>9.2f} {:>9.2f} {:>9.2f} {:>10.3f} {:>9.3f} {:>8} {:>7} {:>6}\n", n, polls,
                               percentile(ms, 0.5), percentile(ms, 0.9), percentile(ms, 1.0), mean_gap,
                               gaps.empty() ? 0 : *std::max_element(gaps.begin(), gaps.end()), at_best, proved, found)
                << std::flush;
    }
  }
  std::cout << "# load average after: " << load_average() << '\n';
  return 0;
}
