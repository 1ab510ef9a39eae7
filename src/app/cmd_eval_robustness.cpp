// `rondo eval robustness DEPLOYMENT... [--days N] [--seeds SPEC] [--alphas LIST] [--navigation-alphas LIST]
// [--route-thresholds LIST]
// [--variants NAMES] [--jobs J] [--json]`: each deployment lived under expected-value scheduling,
// the chance constraint at each α, idle and planned charging, and travel along the route at each
// threshold, for every seed; totals and ratios against the expected-value baseline
// (robustness.h, docs/scheduling.md "Slack sized by risk").
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "commands.h"
#include "number_options.h"
#include "robustness.h"

namespace rondo::app {
namespace {

struct EvalRobustnessArgs {
  std::vector<std::string> deployments;
  std::optional<int> days;
  std::string seeds = "1-5";
  std::vector<double> alphas{0.3, 0.2, 0.1};
  std::vector<double> navigation_alphas;
  std::vector<double> route_thresholds{30};  // seconds
  std::vector<std::string> only;
  int jobs = 2;
  bool json = false;
};

// A seed as `rondo run --seed` and a deployment's `seed:` take it: 0 to 2^63 - 1.
Result<std::uint64_t> seed_number(std::string_view s) {
  std::int64_t v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size() || v < 0)
    return Error::invalid(fmt::format("'{}' is not a seed (a whole number from 0 to {})", s, kMaxWholeNumber));
  return static_cast<std::uint64_t>(v);
}

}  // namespace

// "5" (seeds 1 to 5), "101-105", or "1,4,9".
Result<std::vector<std::uint64_t>> parse_seeds(std::string_view spec) {
  std::vector<std::uint64_t> out;
  if (spec.find_first_of(",-") == std::string_view::npos) {
    RONDO_ASSIGN_OR_RETURN(const std::uint64_t k, seed_number(spec));
    if (k < 1 || k > 1000) return Error::invalid(fmt::format("--seeds: {} is not a count from 1 to 1000", k));
    for (std::uint64_t s = 1; s <= k; ++s) out.push_back(s);
    return out;
  }
  if (const auto dash = spec.find('-'); dash != std::string_view::npos && spec.find(',') == std::string_view::npos) {
    RONDO_ASSIGN_OR_RETURN(const std::uint64_t a, seed_number(spec.substr(0, dash)));
    RONDO_ASSIGN_OR_RETURN(const std::uint64_t b, seed_number(spec.substr(dash + 1)));
    if (b < a || b - a >= 1000) return Error::invalid(fmt::format("--seeds: '{}' is not a range of up to 1000", spec));
    for (std::uint64_t i = 0; i <= b - a; ++i) out.push_back(a + i);
    return out;
  }
  while (!spec.empty()) {
    const auto comma = spec.find(',');
    RONDO_ASSIGN_OR_RETURN(const std::uint64_t s, seed_number(spec.substr(0, comma)));
    out.push_back(s);
    spec = comma == std::string_view::npos ? std::string_view{} : spec.substr(comma + 1);
  }
  return out;
}

namespace {

void run_eval_robustness(const EvalRobustnessArgs& args, CommandContext& ctx) {
  RobustnessOptions options;
  for (const std::string& file : args.deployments) {
    auto d = load_deployment(file);
    if (!d) return (void)fail(ctx, d.error());
    if (d->has_vehicle())
      return (void)fail(ctx, Error::invalid(file + ": robustness runs simulated robots, not vehicles"));
    options.deployments.push_back(std::move(*d));
  }
  auto seeds = parse_seeds(args.seeds);
  if (!seeds) return (void)fail(ctx, seeds.error().with_context("--seeds"));
  options.seeds = std::move(*seeds);
  options.days = args.days;
  for (double a : args.alphas)
    if (!(a > 0 && a <= 0.5)) return (void)fail(ctx, Error::invalid(fmt::format("--alphas: {} is not in (0, 0.5]", a)));
  options.alphas = args.alphas;
  for (double a : args.navigation_alphas)
    if (!(a > 0 && a <= 0.5))
      return (void)fail(ctx, Error::invalid(fmt::format("--navigation-alphas: {} is not in (0, 0.5]", a)));
  options.navigation_alphas = args.navigation_alphas;
  options.route_thresholds.clear();
  for (double t : args.route_thresholds) {
    if (!(t >= 1 && t <= 3600))
      return (void)fail(ctx, Error::invalid(fmt::format("--route-thresholds: {} is not from 1 to 3600 seconds", t)));
    options.route_thresholds.push_back(milliseconds(static_cast<std::int64_t>(std::llround(t * 1000))));
  }
  options.only = args.only;
  options.jobs = args.jobs;
  auto result = evaluate_robustness(options);
  if (!result) return (void)fail(ctx, result.error());
  if (args.json)
    ctx.out << robustness_json(*result).dump(2) << '\n';
  else
    ctx.out << robustness_table(*result);
}

}  // namespace

void add_eval_robustness_command(CLI::App* eval, CommandContext& ctx) {
  auto args = std::make_shared<EvalRobustnessArgs>();
  auto* robustness = eval->add_subcommand(
      "robustness", "Deployments under expected-value and risk-aware scheduling, and idle against planned charging");
  robustness->add_option("deployments", args->deployments, "Deployment files")->required();
  robustness->add_option("--days", args->days, "Days of each run (default: each deployment's own)")
      ->transform(whole_number(1, 3660));
  robustness->add_option("--seeds", args->seeds, "Seeds: a count K (1..K), a range A-B, or a list A,B,C")
      ->capture_default_str();
  robustness->add_option("--alphas", args->alphas, "Values of the chance constraint's α to compare")
      ->delimiter(',')
      ->capture_default_str();
  robustness->add_option("--navigation-alphas", args->navigation_alphas,
                         "For each α, variants whose navigation monitor stops journeys past these levels' quantiles "
                         "(ExecutorOptions::navigation_alpha)")
      ->delimiter(',');
  robustness->add_option("--route-thresholds", args->route_thresholds,
                         "Thresholds in seconds of the variants along the route (ExecutorOptions::route_threshold)")
      ->delimiter(',')
      ->capture_default_str();
  robustness->add_option("--variants", args->only,
                         "Run only these variants (names as in the table, comma-separated), and 'expected'")
      ->delimiter(',');
  robustness->add_option("--jobs", args->jobs, "Runs at once")->capture_default_str()->transform(whole_number(1, 64));
  robustness->add_flag("--json", args->json, "Print JSON instead of a table");
  robustness->callback([args, &ctx] { run_eval_robustness(*args, ctx); });
}

}  // namespace rondo::app
