// `rondo eval robustness` (docs/scheduling.md, "Slack sized by risk"; docs/executor.md,
// "Battery"): each deployment lived on the simulated robot under several variants of the executor
// and several seeds, and what each variant gives against the expected-value baseline measured in
// the same evaluation: tasks completed, failures by reason, waiting, the lowest state of charge.
//
//   RobustnessOptions o{.deployments = {*load_deployment("examples/g4s/deployment.yaml")},
//                       .seeds = {101, 102, 103}, .days = 21};
//   Result<RobustnessResult> r = evaluate_robustness(o);
//   std::cout << robustness_table(*r);
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "deployment.h"
#include "rondo/core/document.h"
#include "rondo/core/result.h"

namespace rondo::app {

// One way of running the executor.
struct RobustnessVariant {
  std::string name;
  std::optional<double> risk_alpha{};  // the chance constraint; nothing: expected values
  std::optional<double> navigation_alpha{};  // the monitor's level under it; nothing: risk_alpha
  bool idle_charging = false;          // charge only when idle at the dock: no hard threshold, no planning
  bool planned_charging = false;       // charges planned by the schedule (ExecutorOptions::battery_planning)
  std::optional<Duration> route_threshold{};  // travel along the route (ExecutorOptions::route_threshold)
};

// The variants compared: expected values first (the baseline), then one per α and, for each α, one
// per navigation α ("alpha 0.1 nav 0.02"), then idle charging and planned charging, then one along
// the route per threshold ("along route 30s").
std::vector<RobustnessVariant> robustness_variants(const std::vector<double>& alphas,
                                                   const std::vector<Duration>& route_thresholds = {},
                                                   const std::vector<double>& navigation_alphas = {});

// What one run gave, from its report.
struct RunFiguresSummary {
  int added = 0;
  int completed = 0;
  int too_late = 0;            // failed too late, and dropped after the robot had left for it
  int navigation_overrun = 0;  // failed on a navigation overrun
  int battery = 0;             // failed or dropped for charging, plus days the robot ran flat
  int other_failures = 0;      // every other failure
  int dropped = 0;             // dropped for good before the robot left for it, any reason but charging
  double waiting_s = 0;
  double lowest_charge = 1;
  int days_flat = 0;
};

struct RobustnessRun {
  std::size_t deployment_index = 0;  // in RobustnessOptions::deployments (two may share a name)
  std::string deployment;
  std::string variant;
  std::uint64_t seed = 0;
  RunFiguresSummary figures{};
  double wall_seconds = 0;
};

struct RobustnessOptions {
  std::vector<Deployment> deployments;
  std::vector<std::uint64_t> seeds{1, 2, 3, 4, 5};
  std::optional<int> days{};           // nothing: each deployment's own
  std::vector<double> alphas{0.3, 0.2, 0.1};
  std::vector<double> navigation_alphas{};
  std::vector<Duration> route_thresholds{seconds(30)};  // 30 s: chosen on validation seeds 101-105
  // When not empty, only the variants of these names run (and the baseline, always).
  std::vector<std::string> only{};
  int jobs = 2;                        // runs at once
};

struct RobustnessResult {
  std::vector<RobustnessVariant> variants;
  std::vector<RobustnessRun> runs;  // deployment-major, then variant, then seed
  std::vector<std::uint64_t> seeds;
  int days = 0;
};

// --seeds: "5" (seeds 1 to 5), "101-105", or "1,4,9".
Result<std::vector<std::uint64_t>> parse_seeds(std::string_view spec);

// Reads the figures of one run out of its report.json.
RunFiguresSummary summarize_report(const Json& report);

// Every run, each in its own temporary folder (removed after). An error when a run fails.
Result<RobustnessResult> evaluate_robustness(const RobustnessOptions& options);

// Per deployment and variant: totals over the seeds, and ratios against the deployment's
// expected-value variant.
std::string robustness_table(const RobustnessResult& result);
Json robustness_json(const RobustnessResult& result);

}  // namespace rondo::app
