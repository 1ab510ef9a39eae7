#include "robustness.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <atomic>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>

#include <unistd.h>

#include "run_session.h"

namespace rondo::app {
namespace {

int count_of(const Json& by_reason, const std::string& reason) {
  return by_reason.contains(reason) ? by_reason[reason].get<int>() : 0;
}

int total(const Json& by_reason) {
  int n = 0;
  for (const auto& [reason, k] : by_reason.items()) n += k.get<int>();
  return n;
}

Deployment variant_of(const Deployment& base, const RobustnessVariant& v, std::uint64_t seed, std::optional<int> days) {
  Deployment d = base;
  d.seed = seed;
  if (days) d.days = *days;
  d.executor.risk_alpha = v.risk_alpha;
  d.executor.navigation_alpha = v.navigation_alpha;
  if (v.idle_charging) d.executor.battery_threshold = 0, d.executor.battery_planning = false;
  if (v.planned_charging) d.executor.battery_planning = true;
  if (v.route_threshold) d.executor.route_threshold = v.route_threshold;
  return d;
}

// A fresh folder for one run under the system's temporary folder.
std::filesystem::path run_folder(std::size_t index) {
  static std::atomic<std::uint64_t> serial{0};
  return std::filesystem::temp_directory_path() /
         fmt::format("rondo-robustness-{}-{}-{}", ::getpid(), index, serial.fetch_add(1));
}

double ratio(double x, double base) { return base > 0 ? x / base : (x > 0 ? INFINITY : 1.0); }

}  // namespace

std::vector<RobustnessVariant> robustness_variants(const std::vector<double>& alphas,
                                                   const std::vector<Duration>& route_thresholds,
                                                   const std::vector<double>& navigation_alphas) {
  std::vector<RobustnessVariant> v{{.name = "expected"}};
  for (double a : alphas) {
    v.push_back({.name = fmt::format("alpha {:g}", a), .risk_alpha = a});
    for (double n : navigation_alphas)
      v.push_back({.name = fmt::format("alpha {:g} nav {:g}", a, n), .risk_alpha = a, .navigation_alpha = n});
  }
  v.push_back({.name = "idle charging", .idle_charging = true});
  v.push_back({.name = "planned charging", .planned_charging = true});
  for (Duration d : route_thresholds)
    v.push_back({.name = fmt::format("along route {:g}s", to_seconds(d)), .route_threshold = d});
  return v;
}

RunFiguresSummary summarize_report(const Json& report) {
  RunFiguresSummary s;
  const Json& t = report["tasks"];
  s.added = t["added"].get<int>();
  s.completed = t["completed"].get<int>();
  const Json& failed = t["failed"];
  const Json& dropped = t["dropped"];
  // A task dropped after the robot had left for it missed its window on the way (its journey came
  // back and it could not be met again): late, like one that failed too late.
  const Json after = t.value("dropped_after_leaving", Json::object());
  const int late_after_leaving = total(after) - count_of(after, "charging");
  s.too_late = count_of(failed, "too late") + late_after_leaving;
  s.navigation_overrun = count_of(failed, "navigation overrun");
  const Json& b = report["battery"];
  s.days_flat = b.value("days_flat", 0);
  s.battery = count_of(failed, "charging") + count_of(dropped, "charging") + s.days_flat;
  s.other_failures = total(failed) - s.too_late - s.navigation_overrun - count_of(failed, "charging");
  s.dropped = total(dropped) - count_of(dropped, "charging") - late_after_leaving;
  s.waiting_s = report["time_s"]["waiting"].get<double>();
  s.lowest_charge = b.value("lowest", 1.0);
  return s;
}

Result<RobustnessResult> evaluate_robustness(const RobustnessOptions& options) {
  RobustnessResult result{
      .variants = robustness_variants(options.alphas, options.route_thresholds, options.navigation_alphas),
      .runs = {},
      .seeds = options.seeds};
  if (!options.only.empty()) {
    const std::string baseline = result.variants.front().name;
    std::erase_if(result.variants, [&](const RobustnessVariant& v) {
      return v.name != baseline && std::find(options.only.begin(), options.only.end(), v.name) == options.only.end();
    });
  }
  struct Job {
    std::size_t index;
    const Deployment* deployment;
    const RobustnessVariant* variant;
    std::uint64_t seed;
  };
  std::vector<Job> jobs;
  for (std::size_t i = 0; i < options.deployments.size(); ++i)
    for (const RobustnessVariant& v : result.variants)
      for (std::uint64_t seed : options.seeds) jobs.push_back({i, &options.deployments[i], &v, seed});
  result.runs.resize(jobs.size());
  result.days = options.days ? *options.days : (options.deployments.empty() ? 0 : options.deployments.front().days);

  std::atomic<std::size_t> next{0};
  std::mutex failed_mutex;
  std::optional<Error> failed;
  const auto work = [&] {
    for (std::size_t i = next++; i < jobs.size(); i = next++) {
      {
        const std::lock_guard lock(failed_mutex);
        if (failed) return;
      }
      const Job& job = jobs[i];
      RunRequest request;
      request.deployment = variant_of(*job.deployment, *job.variant, job.seed, options.days);
      request.out = run_folder(i);
      std::ostringstream quiet;
      Result<RunResult> run = run_deployment(request, quiet);
      std::error_code ignored;
      std::filesystem::remove_all(request.out, ignored);
      if (!run) {
        const std::lock_guard lock(failed_mutex);
        failed = run.error().with_context(fmt::format("{} ({}, seed {})", job.deployment->name, job.variant->name,
                                                      job.seed));
        return;
      }
      result.runs[i] = {.deployment_index = job.index,
                        .deployment = job.deployment->name,
                        .variant = job.variant->name,
                        .seed = job.seed,
                        .figures = summarize_report(run->report),
                        .wall_seconds = run->wall_seconds};
    }
  };
  std::vector<std::jthread> threads;
  for (int k = 1; k < std::max(1, options.jobs); ++k) threads.emplace_back(work);
  work();
  threads.clear();
  if (failed) return *failed;
  return result;
}

namespace {

// Totals over the seeds of one deployment and variant (sum.lowest_charge: the lowest of them).
struct Totals {
  RunFiguresSummary sum{.lowest_charge = 1};
  int runs = 0;
};

// Keyed by the deployment's position among the arguments and the variant's name.
using TotalsKey = std::pair<std::size_t, std::string>;

std::map<TotalsKey, Totals> totals_of(const RobustnessResult& r) {
  std::map<TotalsKey, Totals> out;
  for (const RobustnessRun& run : r.runs) {
    Totals& t = out[{run.deployment_index, run.variant}];
    const RunFiguresSummary& f = run.figures;
    t.sum.added += f.added;
    t.sum.completed += f.completed;
    t.sum.too_late += f.too_late;
    t.sum.navigation_overrun += f.navigation_overrun;
    t.sum.battery += f.battery;
    t.sum.other_failures += f.other_failures;
    t.sum.dropped += f.dropped;
    t.sum.waiting_s += f.waiting_s;
    t.sum.days_flat += f.days_flat;
    t.sum.lowest_charge = std::min(t.sum.lowest_charge, f.lowest_charge);
    ++t.runs;
  }
  return out;
}

// Each deployment once, in the order given: its position and its name.
std::vector<std::pair<std::size_t, std::string>> deployments_in_order(const RobustnessResult& r) {
  std::vector<std::pair<std::size_t, std::string>> out;
  for (const RobustnessRun& run : r.runs)
    if (std::none_of(out.begin(), out.end(), [&](const auto& d) { return d.first == run.deployment_index; }))
      out.emplace_back(run.deployment_index, run.deployment);
  return out;
}

}  // namespace

Json robustness_json(const RobustnessResult& r) {
  Json out = Json::object();
  out["days"] = r.days;
  out["seeds"] = r.seeds;
  const auto totals = totals_of(r);
  Json rows = Json::array();
  for (const auto& [index, d] : deployments_in_order(r)) {
    const Totals& base = totals.at({index, r.variants.front().name});
    const int base_late = base.sum.too_late + base.sum.navigation_overrun;
    for (const RobustnessVariant& v : r.variants) {
      const Totals& t = totals.at({index, v.name});
      const int late = t.sum.too_late + t.sum.navigation_overrun;
      Json row = {{"deployment", d},
                  {"variant", v.name},
                  {"runs", t.runs},
                  {"added", t.sum.added},
                  {"completed", t.sum.completed},
                  {"failed", {{"too_late", t.sum.too_late},
                              {"navigation_overrun", t.sum.navigation_overrun},
                              {"battery", t.sum.battery},
                              {"other", t.sum.other_failures}}},
                  {"dropped", t.sum.dropped},
                  {"waiting_h", t.sum.waiting_s / 3600},
                  {"lowest_charge", t.sum.lowest_charge},
                  {"days_flat", t.sum.days_flat},
                  {"completed_ratio", ratio(t.sum.completed, base.sum.completed)},
                  {"late_and_overrun_ratio", ratio(late, base_late)}};
      if (v.risk_alpha) row["alpha"] = *v.risk_alpha;
      if (v.navigation_alpha) row["navigation_alpha"] = *v.navigation_alpha;
      rows.push_back(std::move(row));
    }
  }
  out["rows"] = std::move(rows);
  Json runs = Json::array();
  for (const RobustnessRun& run : r.runs) {
    const RunFiguresSummary& f = run.figures;
    runs.push_back({{"deployment", run.deployment}, {"variant", run.variant}, {"seed", run.seed},
                    {"added", f.added}, {"completed", f.completed}, {"too_late", f.too_late},
                    {"navigation_overrun", f.navigation_overrun}, {"battery", f.battery},
                    {"other_failures", f.other_failures}, {"dropped", f.dropped}, {"waiting_s", f.waiting_s},
                    {"lowest_charge", f.lowest_charge}, {"days_flat", f.days_flat},
                    {"wall_seconds", run.wall_seconds}});
  }
  out["runs"] = std::move(runs);
  return out;
}

std::string robustness_table(const RobustnessResult& r) {
  std::string out = fmt::format("{} days, seeds {}; totals over the seeds, ratios against 'expected' of the same "
                                "deployment\n\n",
                                r.days, fmt::join(r.seeds, " "));
  out += fmt::format("{:<14} {:<14} {:>6} {:>9} {:>8} {:>8} {:>7} {:>6} {:>7} {:>9} {:>7} {:>10} {:>11}\n",
                     "deployment", "variant", "added", "completed", "too late", "nav over", "battery", "other",
                     "dropped", "waiting h", "lowest", "completed", "late+over");
  const Json j = robustness_json(r);
  for (const Json& row : j["rows"]) {
    const Json& f = row["failed"];
    out += fmt::format("{:<14} {:<14} {:>6} {:>9} {:>8} {:>8} {:>7} {:>6} {:>7} {:>9.1f} {:>6.0f}% {:>9.3f}x {:>10.3f}x\n",
                       row["deployment"].get<std::string>(), row["variant"].get<std::string>(),
                       row["added"].get<int>(), row["completed"].get<int>(), f["too_late"].get<int>(),
                       f["navigation_overrun"].get<int>(), f["battery"].get<int>(), f["other"].get<int>(),
                       row["dropped"].get<int>(), row["waiting_h"].get<double>(),
                       row["lowest_charge"].get<double>() * 100, row["completed_ratio"].get<double>(),
                       row["late_and_overrun_ratio"].get<double>());
  }
  return out;
}

}  // namespace rondo::app
