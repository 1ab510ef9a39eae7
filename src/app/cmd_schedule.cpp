// `rondo schedule`: solve one scheduling problem from a file and print the schedule.
//
//   rondo schedule day.yaml --solver default --time-limit 2 --json
//   rondo schedule --tsptw ../shared/data/trptw/dumas/n20w20.001.tsptw --time-limit 1 --json
//   rondo schedule --vrptw /work/data-vrptw/solomon/R101.txt --time-limit 30 -o r101.sol
#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "cmd_schedule_fleet.h"
#include "commands.h"
#include "number_options.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/schedule/mip_scheduler.h"
#include "rondo/schedule/problem_codec.h"
#include "rondo/schedule/tsptw.h"

namespace rondo::app {

namespace {

double steady_seconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

constexpr double kMaxTimeLimitSeconds = 7 * 24 * 3600.0;  // a week

struct ScheduleOptions {
  std::string file;
  std::string tsptw;
  std::string vrptw;
  std::string pdptw;
  std::string output;
  std::string solver = "default";
  double time_limit = 10;
  bool json = false;
  std::int64_t seed = 1;
};

void run_schedule(const ScheduleOptions& o, CommandContext& ctx) {
  using namespace rondo::schedule;
  const bool tsptw = !o.tsptw.empty();
  const int inputs = !o.file.empty() + tsptw + !o.vrptw.empty() + !o.pdptw.empty();
  if (inputs != 1) {
    fail(ctx, Error::invalid("schedule: give one of a problem FILE, --tsptw FILE, --vrptw FILE or --pdptw FILE"));
    return;
  }
  // NaN passes CLI11's PositiveNumber (every comparison with it is false), and a solver told to
  // stop at NaN never stops: the limit is checked here, bounds and all.
  if (!(std::isfinite(o.time_limit) && o.time_limit > 0 && o.time_limit <= kMaxTimeLimitSeconds)) {
    fail(ctx, Error::invalid(fmt::format("--time-limit: must be a number of seconds above 0 and at most {:g}, not {}",
                                         kMaxTimeLimitSeconds, o.time_limit)));
    return;
  }
  if (!o.vrptw.empty() || !o.pdptw.empty()) {
    run_fleet_benchmark({.vrptw = o.vrptw, .pdptw = o.pdptw, .output = o.output, .time_limit = o.time_limit,
                         .seed = o.seed, .json = o.json},
                        ctx);
    return;
  }
  if (!o.output.empty()) {
    fail(ctx, Error::invalid("-o: only with --vrptw or --pdptw"));
    return;
  }
  Result<Problem> problem = tsptw ? load_tsptw(o.tsptw) : load_problem(o.file);
  if (!problem) {
    fail(ctx, problem.error());
    return;
  }
  if (auto ok = validate(*problem); !ok) {
    fail(ctx, ok.error().with_context(tsptw ? o.tsptw : o.file));
    return;
  }
  std::unique_ptr<Scheduler> solver;
  if (o.solver == "default") {
    solver = std::make_unique<DefaultScheduler>(DefaultSchedulerOptions{.seed = static_cast<std::uint64_t>(o.seed)});
  } else if (o.solver == "mip" || o.solver == "mip-ia") {
    if (auto ok = MipScheduler::check_supported(*problem); !ok) {
      fail(ctx, ok.error());
      return;
    }
    solver = std::make_unique<MipScheduler>(MipOptions{.interval_algebra = o.solver == "mip-ia",
                                                       .time_limit = from_seconds(o.time_limit)});
  } else {
    fail(ctx, Error::invalid(fmt::format("--solver: unknown solver '{}' (default, mip, mip-ia)", o.solver)));
    return;
  }
  const double started = steady_seconds();
  const DeadlineStop stop(steady_seconds, started + o.time_limit);
  Schedule s = solver->solve(*problem, stop);
  s.seconds = steady_seconds() - started;
  const CheckReport check = check_schedule(*problem, s);
  if (!check.ok()) {
    fail(ctx, Error::internal("the schedule failed its check:\n" + check.summary()));
    return;
  }
  // TSPTW objectives are printed in the file's units (seconds here); ours in seconds too.
  const double objective = to_seconds(s.objective);
  if (o.json) {
    Json j = schedule_to_json(*problem, s);
    j["objective"] = tsptw ? Json(tsptw_units(s.objective)) : Json(objective);
    ctx.out << j.dump() << '\n';
  } else {
    ctx.out << fmt::format("status     {}\nobjective  {}\nseconds    {:.3f}\n", to_string(s.status),
                           tsptw ? fmt::format("{}", tsptw_units(s.objective)) : fmt::format("{:.3f} s", objective),
                           s.seconds);
    if (auto g = s.gap()) ctx.out << fmt::format("gap        {:.4f} %\n", *g * 100);
    ctx.out << "order     ";
    for (const auto& e : s.entries) ctx.out << ' ' << problem->tasks[e.task].id;
    ctx.out << '\n';
    for (const auto& d : s.dropped) ctx.out << fmt::format("dropped    {}: {}\n", problem->tasks[d.task].id, d.reason);
  }
  if (s.status == SolveStatus::kInfeasible || s.status == SolveStatus::kTimeout) ctx.exit_code = 1;
}

}  // namespace

void add_schedule_commands(CLI::App& root, CommandContext& ctx) {
  auto options = std::make_shared<ScheduleOptions>();
  CLI::App* cmd = root.add_subcommand("schedule", "Schedule the tasks of a problem file (or a TSPTW instance)");
  cmd->add_option("FILE", options->file, "problem file (JSON or YAML, see docs/scheduling.md)");
  cmd->add_option("--tsptw", options->tsptw, "a TSPTW instance in the LKH-3 format instead of FILE");
  cmd->add_option("--vrptw", options->vrptw, "a VRPTW instance (Solomon / Gehring-Homberger format): the fleet scheduler");
  cmd->add_option("--pdptw", options->pdptw, "a PDPTW instance (Li & Lim format): the fleet scheduler");
  cmd->add_option("-o,--output", options->output, "with --vrptw/--pdptw: write the routes here ('Route 1: 5 3 7')");
  cmd->add_option("--solver", options->solver, "default | mip | mip-ia")->capture_default_str();
  cmd->add_option("--time-limit", options->time_limit, "seconds")->capture_default_str()->check(CLI::PositiveNumber);
  cmd->add_option("--seed", options->seed, "random seed of the default scheduler")
      ->capture_default_str()
      ->transform(whole_number(0, kMaxWholeNumber));
  cmd->add_flag("--json", options->json, "print JSON");
  cmd->callback([options, &ctx] { run_schedule(*options, ctx); });
}

}  // namespace rondo::app
