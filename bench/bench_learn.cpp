// Benchmarks of rondo::learn on the Witham Wharf log (a small harness that prints a table of
// medians; run by hand, never as a test):
//
//   build/bench/bench_learn [WITHAM_DIR]                 # timings
//   build/bench/bench_learn [WITHAM_DIR] --export DIR    # also write the derived binary series
//   build/bench/bench_learn --weekly-calibration         # the weekly term's evidence on synthetic series
//   build/bench/bench_learn [WITHAM_DIR] --weekly-choices UNTIL [--zone Z]  # each edge's choice, fitted before UNTIL
//   build/bench/bench_learn --export-g4s DIR             # binary series from the simulated G4S building
//
// The exported series (`unix_time state` lines, split at 2014-09-02T16:24:00Z) feed
// `rondo eval binary --train DIR/X.train --test DIR/X.test`; see docs/learning.md.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "learn/series.h"
#include "rondo/core/timezone.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/derived_series.h"
#include "rondo/learn/edge_models.h"
#include "rondo/learn/fremen.h"
#include "rondo/map/map_loader.h"
#include "rondo/sim/sim_world.h"

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

// How often the time-of-week term is chosen on series with no weekly structure (false positives,
// by threshold) and with a Wednesday-afternoon closure (power), for series of 2 to 8 weeks. What
// EpisodeOptions::weekly_evidence was set from; no data set is involved.
// The choices on one kind of series: share with z at or above each threshold, share chosen (z >= 2
// and won in two weeks), and the extreme z.
struct Tally {
  static constexpr std::array<double, 3> kThresholds{2.0, 2.5, 3.0};
  std::array<int, 3> hits{};
  int chosen = 0, runs = 0;
  double min_z = 1e9, max_z = -1e9;
  void add(const WeeklyChoice& c) {
    ++runs;
    for (std::size_t k = 0; k < kThresholds.size(); ++k) hits[k] += c.evidence >= kThresholds[k] ? 1 : 0;
    chosen += c.weekly ? 1 : 0;
    min_z = std::min(min_z, c.evidence);
    max_z = std::max(max_z, c.evidence);
  }
  void print(const std::string& what) const {
    const double n = runs;
    fmt::print("{:<44} {:>5} {:>7.3f} {:>7.3f} {:>7.3f} {:>7.3f} {:>7.2f} {:>7.2f}\n", what, runs, hits[0] / n,
               hits[1] / n, hits[2] / n, chosen / n, min_z, max_z);
  }
};

void weekly_calibration() {
  std::mt19937_64 rng(19);
  auto uniform = [&] { return std::uniform_real_distribution<double>(0.0, 1.0)(rng); };
  auto choice = [](const std::vector<BinarySample>& series) { return fit_episode_binary(series)->model().weekly(); };
  fmt::print("{:<44} {:>5} {:>7} {:>7} {:>7} {:>7} {:>7} {:>7}\n", "series", "runs", "z>=2", "z>=2.5", "z>=3", "chosen",
             "min z", "max z");
  for (int days : {14, 21, 28, 56}) {
    for (int step : {600, 1800, 3600}) {
      Tally tally;
      for (int r = 0; r < 200; ++r) {
        // No weekly structure: a base rate and a daily sinusoid of random amplitude and phase.
        const double base = 0.1 + 0.8 * uniform(), amp = 0.5 * std::min(base, 1 - base) * uniform();
        const double phase = 6.283185307 * uniform();
        auto p = [&](std::int64_t tow, std::int64_t) {
          return base + amp * std::sin(6.283185307 * static_cast<double>(tow % 86400) / 86400.0 + phase);
        };
        tally.add(choice(testing::bernoulli_series(days, step, p, uniform)));
      }
      tally.print(fmt::format("no week: {} days, every {} min", days, step / 60));
    }
  }
  // Persistent states: a two-state Markov chain (mean stay 2 h open, 1 h closed), sampled every 10
  // minutes, on top of a daily profile: autocorrelated samples, the hardest case for the test.
  for (int days : {14, 21, 28, 56}) {
    Tally tally;
    for (int r = 0; r < 200; ++r) {
      bool open = true;
      auto p = [&](std::int64_t tow, std::int64_t) {
        const double night = (tow % 86400) < 7 * 3600 ? 0.5 : 1.0;
        open = open ? uniform() >= 10.0 / 120.0 * night : uniform() < 10.0 / 60.0;
        return open ? 1.0 : 0.0;
      };
      tally.add(choice(testing::bernoulli_series(days, 600, p, uniform)));
    }
    tally.print(fmt::format("no week: {} days, Markov states, every 10 min", days));
  }
  for (int days : {14, 21, 28}) {
    for (int step : {1800, 3600}) {
      for (double open : {0.95, 0.7}) {
        Tally tally;
        for (int r = 0; r < 100; ++r) {
          auto p = [&](std::int64_t tow, std::int64_t) { return testing::wednesday_closure(tow, open); };
          tally.add(choice(testing::bernoulli_series(days, step, p, uniform)));
        }
        tally.print(fmt::format("Wed 13-17 closed: {} days, every {} min, p {}", days, step / 60, open));
      }
    }
  }
}

// Each edge's weekly choice when fitted on the attempts before `until`.
void weekly_choices(const std::vector<Traversal>& log, Time until, const TimeZone& zone) {
  std::vector<Traversal> before;
  std::set<std::string> ids;
  for (const auto& t : log) {
    if (t.start < until) before.push_back(t);
    ids.insert(t.edge_id);
  }
  std::vector<EdgeSpec> edges;
  for (const auto& id : ids) edges.push_back({id, 0.0});
  EdgeModelsOptions options;
  options.episode.zone = zone;
  auto models = *EdgeModels::fit(edges, before, options);
  fmt::print("{:<28} {:>8} {:>7} {:>8} {:>10} {:>10} {:>6}\n", "edge", "attempts", "scored", "z", "day_brier",
             "week_brier", "weekly");
  for (std::size_t e = 0; e < models->size(); ++e) {
    const EpisodeEdgeModel* m = models->model(e);
    if (!m) continue;
    const WeeklyChoice& c = m->weekly();
    fmt::print("{:<28} {:>8} {:>7} {:>8.2f} {:>10.4f} {:>10.4f} {:>6}", models->spec(e).id, models->attempts(e),
               c.scored, c.evidence, c.day_brier, c.week_brier, c.weekly ? "yes" : "no");
    if (c.evidence >= 1) {
      // The paired Brier difference (week − day) summed per week of the edge's training data.
      std::vector<SlotAttempt> firsts;
      EpisodeStats replay;
      for (const auto& t : before) {
        if (t.edge_id != models->spec(e).id) continue;
        const Attempt a{t.start, t.start + t.duration, to_seconds(t.duration), t.success};
        firsts.push_back(m->priors()->slot_attempt(a.start, a.success));
        firsts.back().first = !replay.in_retry(a.start, *m->priors());
        replay.add(a, *m->priors());
      }
      double previous = 0;
      fmt::print("  per week:");
      for (std::size_t i = 0, week_end = 0; i < firsts.size(); i = week_end) {
        week_end = i;
        while (week_end < firsts.size() && firsts[week_end].day < firsts[i].day + 7) ++week_end;
        const auto prefix =
            choose_weekly(std::span(firsts).first(week_end), m->priors()->first_success, m->priors()->options);
        const double sum = (prefix.week_brier - prefix.day_brier) * static_cast<double>(week_end);
        fmt::print(" {:+.3f}", sum - previous);
        previous = sum;
      }
    }
    fmt::print("\n");
  }
}

// Binary series sampled from the simulated G4S building (examples/g4s/world.yaml, seed 19), four
// weeks of training from Monday 2026-11-23 and two of test: a sensor's view of the dock's door
// (`g4s_door`: can WayPoint1_WayPoint2 be crossed, every 10 minutes; closed out of office hours
// and at weekends, with the world's random failures and bursts) and of the corridor closed on
// Wednesday afternoons (`g4s_corridor`: WayPoint24_WayPoint28 tried every 30 minutes). Each
// series has its own world and random stream.
int export_g4s(const std::filesystem::path& dir) {
  const auto zone = *TimeZone::named("Europe/London");
  auto map = map::load_map("examples/g4s/map.yaml");
  if (!map) {
    std::cerr << "bench_learn: " << map.error().message << " (run from the project root)\n";
    return 2;
  }
  std::filesystem::create_directories(dir);
  const Time start = zone.at(
      std::chrono::year_month_day{std::chrono::year{2026}, std::chrono::November, std::chrono::day{23}}, Duration{0});
  const Time split = start + hours(24 * 28), end = split + hours(24 * 14);
  for (auto [name, edge_id, step] : {std::tuple{"g4s_door", "WayPoint1_WayPoint2", minutes(10)},
                                     std::tuple{"g4s_corridor", "WayPoint24_WayPoint28", minutes(30)}}) {
    auto world = sim::load_world("examples/g4s/world.yaml", *map, zone);
    if (!world) {
      std::cerr << "bench_learn: " << world.error().message << '\n';
      return 2;
    }
    const auto edge = map->find_edge(edge_id);
    if (!edge) {
      std::cerr << "bench_learn: no edge " << edge_id << '\n';
      return 2;
    }
    sim::Rng rng(19);
    std::vector<BinarySample> train, test;
    for (Time t = start; t < end; t += step) {
      (t < split ? train : test).push_back({t, world->edges->sample_edge(*edge, t, rng).success});
    }
    write_series(dir / (std::string(name) + ".train"), train);
    write_series(dir / (std::string(name) + ".test"), test);
    fmt::print("exported {}: {} training and {} test samples\n", name, train.size(), test.size());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = "../shared/data/witham_wharf";
  std::string export_dir, choices_until, zone_name = "Europe/London";  // Witham Wharf, Lincoln (UK)
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--weekly-calibration") {
      weekly_calibration();
      return 0;
    }
    if (arg == "--export-g4s" && i + 1 < argc) return export_g4s(argv[i + 1]);
    if (arg == "--zone" && i + 1 < argc) {
      zone_name = argv[++i];
    } else if (arg == "--weekly-choices" && i + 1 < argc) {
      choices_until = argv[++i];
    } else if (arg == "--export" && i + 1 < argc) {
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
  if (!choices_until.empty()) {
    auto until = parse_time(choices_until);
    if (!until) {
      std::cerr << "bench_learn: --weekly-choices: " << until.error().message << '\n';
      return 2;
    }
    auto zone = TimeZone::named(zone_name);
    if (!zone) {
      std::cerr << "bench_learn: --zone: " << zone.error().message << '\n';
      return 2;
    }
    weekly_choices(*log, *until, *zone);
    return 0;
  }

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
  // The offline duration tables are computed when first read: a fit that reads one offline quantile
  // of every edge costs what every fit cost before; the executor's refit reads none.
  const auto read_offline_quantiles = [&](const EdgeModels& m) {
    for (std::size_t e = 0; e < m.size(); ++e) g_sink = g_sink + m.quantile_seconds(e, at, 0.9);
  };
  const double fit_ns = median_ns(7, 1, [&] {
    models = *EdgeModels::fit(edges, *log, options);
    read_offline_quantiles(*models);
  });
  fmt::print("{:<52} {:>11.1f} ms\n", "EdgeModels::fit, all edges (episode model)", fit_ns / 1e6);
  const double refit_ns =
      median_ns(7, 1, [&] { g_sink = g_sink + (*EdgeModels::fit(edges, *log, options))->expected_seconds(0, at); });
  fmt::print("{:<52} {:>11.1f} ms\n", "the same, no offline quantile read (a nightly refit)", refit_ns / 1e6);
  EdgeModelsOptions averaging = options;
  averaging.episode.duration_mixture = false;
  const double averaging_fit_ns =
      median_ns(7, 1, [&] { read_offline_quantiles(**EdgeModels::fit(edges, *log, averaging)); });
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
