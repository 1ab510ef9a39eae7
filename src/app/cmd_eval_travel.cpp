// `rondo eval travel`: the paper's Table I on the Witham Wharf logs: how far the route and
// origin-destination travel-time estimates of static, FreMEn and episode models fall from the real
// journey durations, trained on none / the first week / the first two weeks / all data before the
// split, offline and online (plan/travel_evaluation.h, docs/planning.md).
#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>

#include "commands.h"
#include "rondo/core/timezone.h"
#include "rondo/core/traversal.h"
#include "rondo/map/map_loader.h"
#include "rondo/plan/travel_evaluation.h"

namespace rondo::app {
namespace {

struct EvalTravelArgs {
  std::string witham_dir;
  std::string split = "2014-09-02T16:24:00Z";
  std::string map_file = "examples/witham/map.yaml";
  std::string zone = "Europe/London";  // Witham Wharf is in Lincoln, UK (as `rondo eval edges`)
  bool json = false;
};

// none, week1, weeks1-2 and all, counted from the first attempt; the test runs from the split to
// the end of the log.
plan::TravelEvaluationOptions witham_windows(std::span<const Traversal> log, Time split) {
  Time first = log.front().start;
  Time last = first;
  for (const Traversal& t : log) {
    first = std::min(first, t.start);
    last = std::max(last, t.start + t.duration);
  }
  plan::TravelEvaluationOptions o;
  o.trainings = {{"none", first, first},
                 {"week1", first, std::min(split, first + hours(24 * 7))},
                 {"weeks1-2", first, std::min(split, first + hours(24 * 14))},
                 {"all", first, split}};
  o.test = {"test", split, last + seconds(1)};
  return o;
}

void run_eval_travel(const EvalTravelArgs& args, CommandContext& ctx) {
  auto split = parse_time(args.split);
  if (!split) return (void)fail(ctx, split.error().with_context("--split"));
  auto zone = TimeZone::named(args.zone);
  if (!zone) return (void)fail(ctx, zone.error().with_context("--zone"));
  auto m = map::load_map(args.map_file);
  if (!m) return (void)fail(ctx, m.error().with_context("--map"));
  auto log = read_witham_logs(args.witham_dir);
  if (!log) return (void)fail(ctx, log.error());
  if (log->empty()) return (void)fail(ctx, Error::invalid("--witham " + args.witham_dir + ": no attempts"));
  plan::TravelEvaluationOptions options = witham_windows(*log, *split);
  options.models.episode.episode.zone = *zone;  // the episode models' time-of-day bins
  auto result = plan::evaluate_travel(*m, *log, options);
  if (!result) return (void)fail(ctx, result.error());
  if (args.json) {
    ctx.out << plan::travel_evaluation_to_json(*result).dump(2) << '\n';
  } else {
    ctx.out << plan::travel_evaluation_to_table(*result);
  }
}

}  // namespace

void add_eval_travel_command(CLI::App* eval, CommandContext& ctx) {
  auto args = std::make_shared<EvalTravelArgs>();
  auto* travel = eval->add_subcommand(
      "travel", "Journey travel-time estimates against real journeys (the paper's Table I)");
  travel->add_option("--witham", args->witham_dir, "Folder of Witham Wharf <From>_<To>.data logs")->required();
  travel->add_option("--split", args->split, "Train before this time, test from it (ISO 8601 with zone)")
      ->capture_default_str();
  travel->add_option("--map", args->map_file, "The map of the logged edges (poses give the distance prior)")
      ->capture_default_str();
  travel->add_option("--zone", args->zone, "IANA time zone of the log (the time-of-day bins)")
      ->capture_default_str();
  travel->add_flag("--json", args->json, "Print JSON instead of a table");
  travel->callback([args, &ctx] { run_eval_travel(*args, ctx); });
}

}  // namespace rondo::app
