// `rondo run`: the main job. Lives a deployment's days on the simulated robot and writes a run
// folder (run_session.h); with no file, the bundled G4S example for 21 days.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <iostream>
#include <memory>

#include "commands.h"
#include "deployment.h"
#include "number_options.h"
#include "run_session.h"

namespace rondo::app {
namespace {

struct RunArgs {
  std::string deployment;
  std::optional<int> days;
  std::optional<std::int64_t> seed;
  std::optional<int> robots;
  std::string out;
  bool realtime = false;
  double speed = 1.0;
  std::string run_for;
  bool json = false;
};

std::string fresh_run_folder() {
  const auto now = std::chrono::floor<std::chrono::seconds>(std::chrono::system_clock::now());
  std::string stamp = format_time(now);  // 2026-11-22T21:05:03Z
  std::erase(stamp, ':');
  return "runs/" + stamp;
}

void run_run(const RunArgs& args, CommandContext& ctx) {
  const std::filesystem::path file =
      args.deployment.empty() ? default_deployment() : std::filesystem::path(args.deployment);
  auto deployment = load_deployment(file);
  if (!deployment) return (void)fail(ctx, deployment.error());
  if (args.days) deployment->days = *args.days;  // the options' ranges are checked as they are read
  if (args.seed) deployment->seed = static_cast<std::uint64_t>(*args.seed);
  if (args.robots) {
    if (static_cast<std::size_t>(*args.robots) > deployment->robots.size())
      return (void)fail(ctx, Error::invalid(fmt::format("--robots: {} is more than the {} robot(s) of {}", *args.robots,
                                                        deployment->robots.size(), file.string())));
    deployment->robots.resize(static_cast<std::size_t>(*args.robots));
  }
  if (!(args.speed > 0 && args.speed <= 1e6))
    return (void)fail(ctx, Error::invalid(fmt::format("--speed: {} is not above 0 (and at most 1e6)", args.speed)));
  if (deployment->has_vehicle() && !args.realtime)
    return (void)fail(ctx, Error::invalid(fmt::format("{}: robot: a vda5050 vehicle moves in real time; run with --realtime",
                                                      file.string())));
  std::optional<Duration> run_for;
  if (!args.run_for.empty()) {
    auto f = parse_duration(args.run_for);
    if (!f || *f <= Duration{0})
      return (void)fail(ctx, Error::invalid(fmt::format("--for: '{}' is not a duration above 0 (e.g. 20m)", args.run_for)));
    run_for = *f;
  }
  RunRequest request{.deployment = std::move(*deployment),
                     .out = std::filesystem::path(args.out.empty() ? fresh_run_folder() : args.out),
                     .realtime = args.realtime,
                     .speed = args.speed,
                     .run_for = run_for,
                     .progress = ::isatty(STDERR_FILENO) == 1 && &ctx.err == &std::cerr};
  if (!args.json)
    ctx.err << fmt::format("rondo run: {} for {} days, seed {}, into {}\n", file.string(), request.deployment.days,
                           request.deployment.seed, request.out.string());
  auto result = run_deployment(request, ctx.err);
  if (!result) return (void)fail(ctx, result.error());
  const Json& r = result->report;
  if (result->already_finished) {
    // Nothing to do: the same command again on a finished run is not an error.
    if (args.json) ctx.out << r.dump(2) << '\n';
    ctx.err << fmt::format("rondo run: {} is a finished run ({} for {} days, seed {}); its report is {}\n",
                           request.out.string(), request.deployment.name, request.deployment.days,
                           request.deployment.seed, (request.out / "report.json").string());
    return;
  }
  if (args.json) {
    ctx.out << r.dump(2) << '\n';
    return;
  }
  const Json& t = r["tasks"];
  const auto count = [](const Json& by_reason) {
    int n = 0;
    for (const auto& [reason, k] : by_reason.items()) n += k.get<int>();
    return n;
  };
  ctx.out << fmt::format("tasks      {} added, {} completed, {} failed, {} dropped, {} cancelled, {} pending\n",
                         t["added"].get<int>(), t["completed"].get<int>(), count(t["failed"]), count(t["dropped"]),
                         count(t["cancelled"]), t["pending"].get<int>());
  ctx.out << fmt::format("events     {} preemptions (back to the queue), {} drops for now, {} re-offers\n",
                         count(r["events"]["preempted"]), count(r["events"]["dropped_for_now"]),
                         count(r["events"]["re_offered"]));
  if (r.contains("assumptions")) {
    const Json& a = r["assumptions"];
    ctx.out << fmt::format("doors      {} seen, {} assumptions broken ({} reschedules), {} opportunities taken, "
                           "{} retries, {} failed still blocked\n",
                           a["door_observations"].get<int>(), a["broken"].get<int>(), a["reschedules"].get<int>(),
                           a["opportunities_taken"].get<int>(), a["retries"].get<int>(),
                           a["failed_blocked"].get<int>());
  }
  const Json& n = r["navigation"];
  ctx.out << fmt::format("navigation {} of {} edge attempts succeeded, {:.0f} m driven\n",
                         n["successes"].get<int>(), n["attempts"].get<int>(), n["distance_m"].get<double>());
  const Json& b = r["battery"];
  ctx.out << fmt::format("battery    lowest {:.0f} %, {} stays on the charger ({:.1f} h), {} times below the hard "
                         "threshold; for charging: {} tasks back in the queue, {} dropped for now, {} failed, {} "
                         "dropped\n",
                         b["lowest"].get<double>() * 100, b["charges"].get<int>(),
                         b["on_charger_s"].get<double>() / 3600, b["below_threshold"].get<int>(),
                         b["for_charging"].value("queued", 0), b["for_charging"].value("dropped for now", 0),
                         b["for_charging"].value("failed", 0), b["for_charging"].value("dropped", 0));
  ctx.out << fmt::format("wall time  {:.1f} s; report: {}\n", result->wall_seconds,
                         (request.out / "report.json").string());
  if (result->write_errors > 0) {
    ctx.err << fmt::format("rondo: {} store writes failed; see run.json\n", result->write_errors);
    ctx.exit_code = 1;
  }
}

}  // namespace

void add_run_commands(CLI::App& root, CommandContext& ctx) {
  auto args = std::make_shared<RunArgs>();
  auto* run = root.add_subcommand("run", "Run the executive on a deployment (default: the bundled G4S example)");
  run->add_option("deployment", args->deployment, "The deployment file (examples/g4s/deployment.yaml)");
  run->add_option("--days", args->days, "Days to run (default: the deployment's)")->transform(whole_number(1, 3660));
  run->add_option("--robots", args->robots,
                  "Run with the deployment's first N robots only (a fleet's baseline; default: all)")
      ->check(CLI::Range(1, 100000));
  run->add_option("--seed", args->seed, "Random seed of the simulated world (default: the deployment's)")
      ->transform(whole_number(0, kMaxWholeNumber));
  run->add_option("--out", args->out,
                  "The run folder (default: a fresh runs/<time> folder); a folder holding this run resumes it");
  run->add_flag("--realtime", args->realtime, "Run on the system clock instead of simulated time");
  run->add_option("--speed", args->speed, "With --realtime: the clock runs this many times faster (default 1)");
  run->add_option("--for", args->run_for, "Stop after this long on rondo's clock (e.g. 20m), before the days end");
  run->add_flag("--json", args->json, "Print report.json instead of a summary");
  run->callback([args, &ctx] { run_run(*args, ctx); });
}

}  // namespace rondo::app
