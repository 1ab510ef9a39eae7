// The fleet scheduler on a folder of routing benchmark instances against a table of best known
// values (issue 39): per instance and in total, the vehicles (ours and the best known), the gap in
// distance where the counts match, and the time to the first feasible plan. One instance at a
// time, in this process; every plan is checked.
//
//   build/bench/bench_fleet_vrp_table vrptw /work/data-vrptw/solomon bench/solomon_best_known.csv 30 [seed] [only]
//   build/bench/bench_fleet_vrp_table pdptw /work/data-vrptw/lilim bench/lilim_best_known.csv 30
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "bench_clock.h"
#include "rondo/schedule/fleet_checker.h"
#include "rondo/schedule/fleet_scheduler.h"
#include "rondo/schedule/vrp_benchmark.h"

using rondo::bench::steady_seconds;
using namespace rondo::schedule;

namespace {

struct Known {
  std::string instance;
  std::size_t vehicles = 0;
  double distance = 0;
};

std::vector<Known> read_table(const std::string& file) {
  std::vector<Known> out;
  std::ifstream in(file);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::stringstream s(line);
    Known k;
    std::string v, d;
    std::getline(s, k.instance, ',');
    std::getline(s, v, ',');
    std::getline(s, d, ',');
    k.vehicles = std::stoul(v);
    k.distance = std::stod(d);
    out.push_back(k);
  }
  return out;
}

std::optional<std::filesystem::path> find_instance(const std::filesystem::path& folder, const std::string& name) {
  for (const std::string& n : {name, fmt::format("{}.txt", name)})
    if (std::filesystem::exists(folder / n)) return folder / n;
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: bench_fleet_vrp_table vrptw|pdptw FOLDER TABLE.csv SECONDS [SEED] [ONLY-PREFIX]\n";
    return 2;
  }
  const bool pdp = std::string(argv[1]) == "pdptw";
  const std::filesystem::path folder = argv[2];
  const double limit = std::atof(argv[4]);
  const std::uint64_t seed = argc > 5 ? std::strtoull(argv[5], nullptr, 10) : 1;
  const std::string only = argc > 6 ? argv[6] : "";
  std::printf("load average before: %s\n", rondo::bench::load_average().c_str());
  std::printf("%-10s %8s %8s %12s %12s %8s %10s %8s\n", "instance", "veh", "best", "distance", "best", "gap %",
              "first s", "checked");
  std::size_t runs = 0, matched = 0;
  double gap_sum = 0, first_sum = 0, first_max = 0;
  for (const Known& k : read_table(argv[3])) {
    if (!only.empty() && k.instance.rfind(only, 0) != 0) continue;
    const auto file = find_instance(folder, k.instance);
    if (!file) continue;
    auto problem = pdp ? load_pdptw(*file) : load_vrptw(*file);
    if (!problem) {
      std::printf("%-10s %s\n", k.instance.c_str(), problem.error().message.c_str());
      continue;
    }
    const double started = steady_seconds();
    double first = -1;
    FleetSchedulerOptions options{.seed = seed};
    options.on_progress = [&](const FleetProgress& p) {
      if (first < 0 && p.unplanned == 0) first = steady_seconds() - started;
    };
    const DeadlineStop stop(steady_seconds, started + limit);
    const FleetPlan plan = FleetScheduler(options).solve(*problem, stop);
    const bool checked = check_fleet_plan(*problem, plan).ok() && plan.dropped.empty();
    const bool same = plan.vehicles == k.vehicles;
    const double gap = 100.0 * (plan.distance - k.distance) / k.distance;
    ++runs;
    if (same) {
      ++matched;
      gap_sum += gap;
    }
    first_sum += first;
    first_max = std::max(first_max, first);
    std::printf("%-10s %8zu %8zu %12.2f %12.2f %8s %10.4f %8s\n", k.instance.c_str(), plan.vehicles, k.vehicles,
                plan.distance, k.distance, same ? fmt::format("{:.2f}", gap).c_str() : "-", first,
                checked ? "yes" : "NO");
    std::fflush(stdout);
  }
  std::printf("\ninstances %zu, best known vehicle count on %zu, mean distance gap there %.3f %%, first feasible "
              "mean %.4f s max %.4f s, %g s each, seed %llu\n",
              runs, matched, matched ? gap_sum / static_cast<double>(matched) : 0.0,
              runs ? first_sum / static_cast<double>(runs) : 0.0, first_max, limit,
              static_cast<unsigned long long>(seed));
  std::printf("load average after: %s\n", rondo::bench::load_average().c_str());
  return 0;
}
