// The fleet scheduler against the robots' anchor (issue 39, "Against the robots' anchor"): robot
// days of the fleet example (bench/fleet_example_days.h), each solved whole by the fleet scheduler
// on a poll budget (deadlines hard: a task it cannot fit is dropped) and by rmf_task's greedy
// allocation (bench/rmf_greedy.h; it ignores deadlines, so it is timed and checked on the day with
// soft deadlines), both answers checked by check_fleet_plan, compared per day on the sum of end
// times (hours from local midnight, every task's end; `flow`: the sum of end - release, the part a
// plan can change), the deadlines met (tasks ended by their window's deadline) and the drops.
//
//   build/bench/bench_fleet_robot_days examples/fleet [days=20] [polls=20000] [seed=1]
//
// Two fleets: the example's 5 robots with its load, and 20 robots (its robots four times over)
// with four times its people's calls. A day is `better` when the fleet scheduler's sum of ends is
// below the baseline's and it meets at least as many deadlines.
#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "fleet_example_days.h"
#include "rmf_greedy.h"
#include "rondo/schedule/fleet_checker.h"
#include "rondo/schedule/fleet_plan.h"
#include "rondo/schedule/fleet_scheduler.h"
#include "rondo/schedule/stop_condition.h"

using namespace rondo;
using schedule::FleetPlan;
using schedule::FleetProblem;

namespace {

struct Figures {
  double sum_of_ends_h = 0;
  double flow_h = 0;
  std::size_t met = 0;
  std::size_t dropped = 0;
  bool checked = false;
};

// `p` is the problem the plan answers; a plan is checked against each of `also` too.
Figures figures(const FleetProblem& p, const FleetPlan& plan, const std::vector<const FleetProblem*>& also = {}) {
  Figures f;
  for (std::size_t r = 0; r < plan.routes.size(); ++r)
    for (const schedule::ScheduledTask& e : plan.routes[r]) {
      f.sum_of_ends_h += to_seconds(e.end - p.robots[r].free_from) / 3600.0;
      f.flow_h += to_seconds(e.end - p.tasks[e.task].task.release) / 3600.0;
      if (e.end <= (p.tasks[e.task].due ? *p.tasks[e.task].due : p.tasks[e.task].task.deadline)) ++f.met;
    }
  f.dropped = plan.dropped.size();
  f.checked = true;
  std::vector<const FleetProblem*> problems{&p};
  problems.insert(problems.end(), also.begin(), also.end());
  for (const FleetProblem* q : problems) {
    const schedule::FleetCheckReport check = schedule::check_fleet_plan(*q, plan);
    f.checked = f.checked && check.ok();
    if (!check.ok()) std::fprintf(stderr, "%s\n", check.summary().c_str());
  }
  return f;
}

struct Totals {
  int better = 0;
  int days = 0;
  double fleet_h = 0, rmf_h = 0, fleet_flow_h = 0, rmf_flow_h = 0;
  std::size_t fleet_met = 0, rmf_met = 0, tasks = 0;
};

void run_fleet(const bench::FleetExample& example, const std::string& title, const bench::ExampleDayOptions& o,
               int days, std::int64_t polls) {
  std::printf("\n%s\n", title.c_str());
  std::printf("%4s %6s | %11s %8s %5s %5s %7s | %11s %8s %5s %5s %6s | %6s\n", "day", "tasks", "fleet sum h", "flow h",
              "met", "drop", "s", "rmf sum h", "flow h", "met", "drop", "s", "better");
  Totals total;
  for (int d = 0; d < days; ++d) {
    Result<FleetProblem> day = example.day(d, o);
    if (!day) {
      std::fprintf(stderr, "day %d: %s\n", d, day.error().message.c_str());
      std::exit(2);
    }
    const FleetProblem& p = *day;
    const FleetProblem soft = example.with_soft_deadlines(p);
    if (auto ok = schedule::validate_fleet(p); !ok) {
      std::fprintf(stderr, "day %d: %s\n", d, ok.error().message.c_str());
      std::exit(2);
    }
    double t0 = bench::steady_seconds();
    const schedule::PollBudgetStop budget(static_cast<std::int64_t>(p.tasks.size()) + polls);
    const FleetPlan fleet = schedule::FleetScheduler({.seed = o.seed}).solve(p, budget);
    const double fleet_s = bench::steady_seconds() - t0;
    t0 = bench::steady_seconds();
    const Result<FleetPlan> rmf = schedule::time_fleet_routes(soft, bench::rmf_greedy_orders(soft), "no robot runs it");
    const double rmf_s = bench::steady_seconds() - t0;
    if (!rmf) {
      std::fprintf(stderr, "day %d: the rmf baseline's routes do not time: %s\n", d, rmf.error().message.c_str());
      std::exit(1);
    }
    const Figures a = figures(p, fleet, {&soft});
    const Figures b = figures(soft, *rmf);
    const bool better =
        a.checked && b.checked && a.sum_of_ends_h < b.sum_of_ends_h && a.met >= b.met && a.dropped <= b.dropped;
    std::printf("%4d %6zu | %11.1f %8.2f %5zu %5zu %7.2f | %11.1f %8.2f %5zu %5zu %6.3f | %6s%s\n", d + 1,
                p.tasks.size(), a.sum_of_ends_h, a.flow_h, a.met, a.dropped, fleet_s, b.sum_of_ends_h, b.flow_h, b.met,
                b.dropped, rmf_s, better ? "yes" : "NO", a.checked && b.checked ? "" : " (a plan failed the checker)");
    std::fflush(stdout);
    total.better += better;
    ++total.days;
    total.fleet_h += a.sum_of_ends_h;
    total.rmf_h += b.sum_of_ends_h;
    total.fleet_flow_h += a.flow_h;
    total.rmf_flow_h += b.flow_h;
    total.fleet_met += a.met;
    total.rmf_met += b.met;
    total.tasks += p.tasks.size();
  }
  std::printf(
      "total: %d of %d days better; sum of ends %.1f h against %.1f h (%.2f h less; flow %.2f h against "
      "%.2f h, %.1f %% less); deadlines met %zu against %zu of %zu\n",
      total.better, total.days, total.fleet_h, total.rmf_h, total.rmf_h - total.fleet_h, total.fleet_flow_h,
      total.rmf_flow_h, 100.0 * (1 - total.fleet_flow_h / total.rmf_flow_h), total.fleet_met, total.rmf_met,
      total.tasks);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_fleet_robot_days EXAMPLE_FOLDER [days=20] [polls=20000] [seed=1]\n");
    return 2;
  }
  const int days = argc > 2 ? std::atoi(argv[2]) : 20;
  const std::int64_t polls = argc > 3 ? std::atoll(argv[3]) : 20000;
  const std::uint64_t seed = argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 1;
  Result<bench::FleetExample> example = bench::FleetExample::load(argv[1]);
  if (!example) {
    std::fprintf(stderr, "%s\n", example.error().message.c_str());
    return 2;
  }
  std::printf("load average before: %s\n", bench::load_average().c_str());
  std::printf(
      "fleet scheduler: %lld search polls after its construction, seed %llu; rmf greedy: in order of "
      "release, to the robot that finishes it first\n",
      static_cast<long long>(polls), static_cast<unsigned long long>(seed));
  run_fleet(*example, "5 robots (the example's), its load", {.copies = 1, .request_factor = 1, .seed = seed}, days,
            polls);
  run_fleet(*example, "20 robots (the example's four times over), four times its people's calls",
            {.copies = 4, .request_factor = 4, .seed = seed}, days, polls);
  std::printf("load average after: %s\n", bench::load_average().c_str());
  return 0;
}
