// Benchmarks of rondo::learn on the Witham Wharf log (a small harness that prints a table of
// medians; run by hand, never as a test):
//
//   build/bench/bench_learn [WITHAM_DIR]                 # timings
//   build/bench/bench_learn [WITHAM_DIR] --export DIR    # also write the derived binary series
//
// The exported series (`unix_time state` lines, split at 2014-09-02T16:24:00Z) feed
// `rondo eval binary --train DIR/X.train --test DIR/X.test`; see docs/learning.md.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "rondo/core/timezone.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/derived_series.h"
#include "rondo/learn/edge_models.h"
#include "rondo/learn/fremen.h"

namespace {

using namespace rondo;
using namespace rondo::learn;
using Clock = std::chrono::steady_clock;

// Median over `rounds` of the time per operation of `batch` (which performs `ops` operations).
template <class F>
double median_ns(int rounds, int ops, F&& batch) {
  std::vector<double> per_op;
  for (int r = 0; r < rounds; ++r) {
    const auto t0 = Clock::now();
    batch();
    const auto t1 = Clock::now();
    per_op.push_back(std::chrono::duration<double, std::nano>(t1 - t0).count() / ops);
  }
  std::sort(per_op.begin(), per_op.end());
  return per_op[per_op.size() / 2];
}

volatile double g_sink = 0;  // keeps the optimiser from dropping predictions

void write_series(const std::filesystem::path& file, const std::vector<BinarySample>& samples) {
  std::ofstream out(file);
  for (const auto& s : samples) {
    out << static_cast<long long>(to_unix_seconds(s.time)) << ' ' << (s.value ? 1 : 0) << '\n';
  }
}

void export_series(const std::vector<Traversal>& log, const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  const Time split = *parse_time("2014-09-02T16:24:00Z");
  const Time from = std::chrono::floor<std::chrono::hours>(log.front().start);
  const Time to = log.back().start;
  auto write_split = [&](const std::string& name, const std::vector<BinarySample>& all) {
    std::vector<BinarySample> train, test;
    for (const auto& s : all) (s.time < split ? train : test).push_back(s);
    write_series(dir / (name + ".train"), train);
    write_series(dir / (name + ".test"), test);
    fmt::print("exported {}: {} training and {} test samples\n", name, train.size(), test.size());
  };
  write_split("docked", presence_at_node(log, "ChargingPoint", from, to, minutes(10)));
  write_split("labdoor", edge_outcomes(log, "LabDoor1_LabDoor2"));
  write_split("kitchen", arrivals_in_slot(log, "Kitchen", from, to, hours(1)));
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = "../shared/data/witham_wharf";
  std::string export_dir;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--export" && i + 1 < argc) {
      export_dir = argv[++i];
    } else {
      dir = arg;
    }
  }
  auto log = read_witham_logs(dir);
  if (!log) {
    std::cerr << "bench_learn: " << log.error().message << '\n';
    return 2;
  }
  if (!export_dir.empty()) export_series(*log, export_dir);

  std::set<std::string> ids;
  for (const auto& t : *log) ids.insert(t.edge_id);
  std::vector<EdgeSpec> edges;
  for (const auto& id : ids) edges.push_back({id, 0.0});
  const Time at = *parse_time("2014-09-03T10:00:00Z");

  fmt::print("{} edges, {} attempts\n", edges.size(), log->size());
  fmt::print("{:<52} {:>14}\n", "operation", "median");

  std::shared_ptr<const EdgeModels> models;
  EdgeModelsOptions options;
  options.episode.zone = *TimeZone::named("Europe/London");  // Witham Wharf, Lincoln (UK)
  const double fit_ns = median_ns(7, 1, [&] { models = *EdgeModels::fit(edges, *log, options); });
  fmt::print("{:<52} {:>11.1f} ms\n", "EdgeModels::fit, all edges (episode model)", fit_ns / 1e6);
  EdgeModelsOptions averaging = options;
  averaging.episode.duration_mixture = false;
  const double averaging_fit_ns =
      median_ns(7, 1, [&] { g_sink = g_sink + (*EdgeModels::fit(edges, *log, averaging))->expected_seconds(0, at); });
  fmt::print("{:<52} {:>11.1f} ms\n", "EdgeModels::fit, duration_mixture = false", averaging_fit_ns / 1e6);

  const double fremen_fit_ns = median_ns(7, 1, [&] {
    for (const auto& id : ids) {
      std::vector<BinarySample> flags;
      for (const auto& t : *log) {
        if (t.edge_id == id) flags.push_back({t.start, t.success});
      }
      g_sink = g_sink + fit_fremen_binary(flags, {.order = 2})->probability(at);
    }
  });
  fmt::print("{:<52} {:>11.1f} ms\n", "fit_fremen_binary, all edges (for comparison)", fremen_fit_ns / 1e6);

  const int n = static_cast<int>(models->size());
  const double predict_ns = median_ns(101, n, [&] {
    for (std::size_t e = 0; e < models->size(); ++e) {
      g_sink = g_sink + models->success_probability(e, at) + models->expected_seconds(e, at) +
               models->quantile_seconds(e, at, 0.9);
    }
  });
  fmt::print("{:<52} {:>11.2f} us\n", "offline p, E[tau], q90 of one edge at t", predict_ns / 1e3);

  LiveEdgeModels live(models);
  const double live_predict_ns = median_ns(101, n, [&] {
    for (std::size_t e = 0; e < models->size(); ++e) {
      g_sink =
          g_sink + live.success_probability(e, at) + live.expected_seconds(e, at) + live.quantile_seconds(e, at, 0.9);
    }
  });
  fmt::print("{:<52} {:>11.2f} us\n", "online p, E[tau], q90 of one edge at t", live_predict_ns / 1e3);

  std::vector<std::pair<std::size_t, Attempt>> stream;
  for (const auto& t : *log) {
    stream.push_back(
        {*models->index_of(t.edge_id), {t.start, t.start + t.duration, to_seconds(t.duration), t.success}});
  }
  const double update_ns = median_ns(11, static_cast<int>(stream.size()), [&] {
    LiveEdgeModels fresh(models);
    for (const auto& [e, a] : stream) fresh.observe(e, a);
  });
  fmt::print("{:<52} {:>11.3f} us\n", "LiveEdgeModels::observe (online update)", update_ns / 1e3);

  const double fremen_update_ns = median_ns(5, static_cast<int>(stream.size()), [&] {
    OnlineFremenBinary fremen(2);
    for (const auto& [e, a] : stream) fremen.observe(a.start, a.end, a.success);
  });
  fmt::print("{:<52} {:>11.3f} us\n", "OnlineFremenBinary::observe (for comparison)", fremen_update_ns / 1e3);
  return g_sink > 0 ? 0 : 0;
}
