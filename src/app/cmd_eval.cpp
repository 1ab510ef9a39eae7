// `rondo eval edges` and `rondo eval binary`: compare the learned models on real logs.
#include <memory>

#include "commands.h"
#include "number_options.h"
#include "rondo/core/timezone.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/evaluation.h"

namespace rondo::app {
void add_eval_travel_command(CLI::App* eval, CommandContext& ctx);      // cmd_eval_travel.cpp
void add_eval_robustness_command(CLI::App* eval, CommandContext& ctx);  // cmd_eval_robustness.cpp
namespace {

struct EvalEdgesArgs {
  std::string witham_dir;
  std::string split = "2014-09-02T16:24:00Z";
  std::string until;
  std::string zone = "Europe/London";  // Witham Wharf is in Lincoln, UK
  int min_train = 20;
  int min_test = 5;
  bool json = false;
};

struct EvalBinaryArgs {
  std::string train_file;
  std::string test_file;
  std::string zone = "UTC";
  bool json = false;
};

void run_eval_edges(const EvalEdgesArgs& args, CommandContext& ctx) {
  auto split = parse_time(args.split);
  if (!split) return (void)fail(ctx, split.error().with_context("--split"));
  learn::EdgeEvalOptions options;
  options.split = *split;
  options.min_train_attempts = args.min_train;
  options.min_test_attempts = args.min_test;
  if (!args.until.empty()) {
    auto until = parse_time(args.until);
    if (!until) return (void)fail(ctx, until.error().with_context("--until"));
    options.until = *until;
  }
  auto zone = TimeZone::named(args.zone);
  if (!zone) return (void)fail(ctx, zone.error().with_context("--zone"));
  options.episode.zone = *zone;
  auto log = read_witham_logs(args.witham_dir);
  if (!log) return (void)fail(ctx, log.error());
  auto result = learn::evaluate_edges(*log, options);
  if (!result) return (void)fail(ctx, result.error());
  if (args.json) {
    ctx.out << learn::evaluation_to_json(*result).dump(2) << '\n';
  } else {
    ctx.out << learn::evaluation_to_table(*result);
  }
}

void run_eval_binary(const EvalBinaryArgs& args, CommandContext& ctx) {
  auto train = learn::read_binary_series(args.train_file);
  if (!train) return (void)fail(ctx, train.error());
  auto test = learn::read_binary_series(args.test_file);
  if (!test) return (void)fail(ctx, test.error());
  auto zone = TimeZone::named(args.zone);
  if (!zone) return (void)fail(ctx, zone.error().with_context("--zone"));
  learn::EpisodeOptions episode;
  episode.zone = *zone;
  auto result = learn::evaluate_binary_series(*train, *test, episode);
  if (!result) return (void)fail(ctx, result.error());
  if (args.json) {
    ctx.out << learn::evaluation_to_json(*result).dump(2) << '\n';
  } else {
    ctx.out << learn::evaluation_to_table(*result);
  }
}

}  // namespace

void add_eval_commands(CLI::App& root, CommandContext& ctx) {
  auto* eval = root.add_subcommand("eval", "Evaluate: learned models on real logs, schedules under risk");
  eval->require_subcommand(1);

  auto edges_args = std::make_shared<EvalEdgesArgs>();
  auto* edges = eval->add_subcommand("edges", "Success and duration models of every edge, offline and online");
  edges->add_option("--witham", edges_args->witham_dir, "Folder of Witham Wharf <From>_<To>.data logs")->required();
  edges->add_option("--split", edges_args->split, "Train before this time, test from it (ISO 8601 with zone)")
      ->capture_default_str();
  edges->add_option("--until", edges_args->until,
                    "Ignore attempts from this time on (a validation split inside the training data)");
  edges->add_option("--zone", edges_args->zone, "IANA time zone of the deployment (time-of-day bins)")
      ->capture_default_str();
  edges->add_option("--min-train", edges_args->min_train, "Attempts an edge needs before the split")
      ->capture_default_str()
      ->transform(whole_number(0, 1000000));
  edges->add_option("--min-test", edges_args->min_test, "Attempts an edge needs after the split")
      ->capture_default_str()
      ->transform(whole_number(0, 1000000));
  edges->add_flag("--json", edges_args->json, "Print JSON instead of a table");
  edges->callback([edges_args, &ctx] { run_eval_edges(*edges_args, ctx); });

  auto binary_args = std::make_shared<EvalBinaryArgs>();
  auto* binary = eval->add_subcommand("binary", "Binary models on one series of 'unix_time state' lines");
  binary->add_option("--train", binary_args->train_file, "Training series")->required();
  binary->add_option("--test", binary_args->test_file, "Test series")->required();
  binary->add_option("--zone", binary_args->zone, "IANA time zone of the series (time-of-day bins)")
      ->capture_default_str();
  binary->add_flag("--json", binary_args->json, "Print JSON instead of a table");
  binary->callback([binary_args, &ctx] { run_eval_binary(*binary_args, ctx); });
  add_eval_travel_command(eval, ctx);
  add_eval_robustness_command(eval, ctx);
}

}  // namespace rondo::app
