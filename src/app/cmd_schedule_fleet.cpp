// `rondo schedule --vrptw FILE` and `--pdptw FILE`: the fleet scheduler on the routing
// benchmarks (Solomon / Gehring-Homberger, Li & Lim): prints vehicles and distance, writes the
// routes in the benchmarks' solution format.
//
//   rondo schedule --vrptw /work/data-vrptw/solomon/R101.txt --time-limit 30 --seed 1 -o r101.sol
#include "cmd_schedule_fleet.h"

#include <chrono>
#include <optional>

#include <fmt/format.h>

#include "rondo/core/atomic_file.h"
#include "rondo/core/document.h"
#include "rondo/schedule/fleet_checker.h"
#include "rondo/schedule/fleet_scheduler.h"
#include "rondo/schedule/vrp_benchmark.h"

namespace rondo::app {

namespace {

double steady_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace

void run_fleet_benchmark(const FleetBenchmarkOptions& o, CommandContext& ctx) {
  using namespace rondo::schedule;
  const bool pdp = !o.pdptw.empty();
  const std::string& file = pdp ? o.pdptw : o.vrptw;
  Result<FleetProblem> problem = pdp ? load_pdptw(file) : load_vrptw(file);
  if (!problem) {
    fail(ctx, problem.error());
    return;
  }
  if (auto ok = validate_fleet(*problem); !ok) {
    fail(ctx, ok.error().with_context(file));
    return;
  }
  const double started = steady_seconds();
  std::optional<double> first_feasible;
  FleetSchedulerOptions options{.seed = static_cast<std::uint64_t>(o.seed)};
  options.on_progress = [&](const FleetProgress& p) {
    if (!first_feasible && p.unplanned == 0) first_feasible = steady_seconds() - started;
  };
  const DeadlineStop stop(steady_seconds, started + o.time_limit);
  FleetPlan plan = FleetScheduler(options).solve(*problem, stop);
  plan.seconds = steady_seconds() - started;
  plan.seconds_to_first = first_feasible.value_or(-1);
  const FleetCheckReport check = check_fleet_plan(*problem, plan);
  if (!check.ok()) {
    fail(ctx, Error::internal("the plan failed its check:\n" + check.summary()));
    return;
  }
  if (!o.output.empty())
    if (auto s = write_file_atomically(o.output, format_routes(*problem, plan)); !s) {
      fail(ctx, s.error());
      return;
    }
  if (o.json) {
    Json j{{"vehicles", plan.vehicles},      {"distance", plan.distance},
                     {"seconds", plan.seconds},        {"first_feasible_seconds", plan.seconds_to_first},
                     {"planned", plan.planned()},      {"dropped", check.dropped},
                     {"tasks", problem->tasks.size()}};
    ctx.out << j.dump() << '\n';
  } else {
    ctx.out << fmt::format("vehicles   {}\ndistance   {:.4f}\nseconds    {:.3f}\nfirst      {:.3f} s\n", plan.vehicles,
                           plan.distance, plan.seconds, plan.seconds_to_first);
    for (const std::string& id : check.dropped) ctx.out << fmt::format("dropped    {}\n", id);
  }
  if (!plan.dropped.empty()) ctx.exit_code = 1;
}

}  // namespace rondo::app
