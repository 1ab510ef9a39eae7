// Speed of the planner on two generated 1,000-place maps with daily-rhythm models: a floor grid
// (building_map) and a corridor building (corridor_building_map: floors of long corridors with
// rooms, like real deployment maps); then the corridor building again with the success rates a
// real robot saw (each edge gets the attempt success rate of one of the 62 Witham Wharf edges,
// read from the logs). Prints tables of medians. Checks issue 4's targets: the exact single-target
// policy under 1 ms; the exact solver at least 100× faster than value iteration at 1e-6 in the
// same run; a 50 × 50 travel matrix for 96 quarter-hour slots under 1 s on one core.
//
//   cmake -S . -B build -G Ninja -DRONDO_BUILD_BENCH=ON && cmake --build build --target bench_plan
//   build/bench/bench_plan [repetitions] [WITHAM_DIR]   # default ../shared/data/witham_wharf
//
// Times are this thread's CPU time (the harness only; the library never reads a clock).
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "plan/random_map.h"
#include "bench_clock.h"
#include "rondo/core/traversal.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/plan/value_iteration.h"

namespace {

using namespace rondo;
using bench::median;
using bench::seconds_of;
using namespace rondo::plan;

// Keeps results alive so the optimiser cannot drop the work.
volatile double g_sink = 0;

void row(const std::string& what, double seconds, std::size_t samples) {
  const std::string value = seconds < 1e-3  ? fmt::format("{:.1f} us", seconds * 1e6)
                            : seconds < 1.0 ? fmt::format("{:.3f} ms", seconds * 1e3)
                                            : fmt::format("{:.3f} s", seconds);
  fmt::print("{:<52} {:>14} {:>8}\n", what, value, samples);
}

// The attempt success rate of every edge log in `dir`, sorted; empty (with a message) when the
// logs cannot be read.
std::vector<double> witham_success_rates(const std::string& dir) {
  auto logs = read_witham_logs(dir);
  if (!logs) {
    fmt::print("(no Witham Wharf rows: {})\n", logs.error().message);
    return {};
  }
  std::map<std::string, std::pair<double, double>> by_edge;  // successes, attempts
  for (const Traversal& t : *logs) {
    auto& [successes, attempts] = by_edge[t.edge_id];
    successes += t.success ? 1.0 : 0.0;
    attempts += 1.0;
  }
  std::vector<double> rates;
  for (const auto& [edge, counts] : by_edge) rates.push_back(counts.first / counts.second);
  std::sort(rates.begin(), rates.end());
  return rates;
}

// daily_models' τ, with p_e the Witham rate at a seeded-random rank (the same for both directions
// of a connection would be more realistic still; independent draws are the simpler choice).
FunctionEdgeModels witham_rate_models(const map::TopoMap& m, const std::vector<double>& rates) {
  const FunctionEdgeModels daily = testing::daily_models(m);
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<std::size_t> pick(0, rates.size() - 1);
  std::vector<double> p;
  for (std::size_t e = 0; e < m.edge_count(); ++e) p.push_back(rates[pick(rng)]);
  return FunctionEdgeModels([daily, p](map::EdgeIndex e, Time t) {
    EdgeCrossing o = daily.outcome(e, t);
    o.success_probability = p[e];
    return o;
  });
}

// M_t construction, the exact solver and value iteration (Jacobi and Gauss-Seidel) at 1e-6 on
// one map, all on the same M_t and targets.
void solver_rows(const map::TopoMap& m, const EdgeModelView& models, const std::string& label, int repetitions) {
  const Time noon = *parse_time("2014-09-02T12:00:00Z");
  fmt::print("\nmap: {}: {} nodes, {} edges, hop diameter {}\n", label, m.node_count(), m.edge_count(),
             testing::hop_diameter(m));
  std::vector<double> find;
  std::shared_ptr<const DeadEnds> dead_ends;
  for (int r = 0; r < 50 * repetitions; ++r)
    find.push_back(seconds_of([&] { dead_ends = std::make_shared<const DeadEnds>(DeadEnds::find(m)); }));
  row(fmt::format("find the dead ends, once per map ({} regions, {} nodes)", dead_ends->region_count(),
                  dead_ends->region_members().size()),
      median(find), find.size());
  std::vector<double> build;
  for (int r = 0; r < 50 * repetitions; ++r) {
    build.push_back(
        seconds_of([&] { g_sink = g_sink + Mdp::build(m, models, noon, dead_ends).expected_crossing_seconds(0); }));
  }
  row("build M_t (models read once; dead ends' exits)", median(build), build.size());

  const Mdp mdp = Mdp::build(m, models, noon, dead_ends);
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<NodeIndex> any(0, m.node_count() - 1);
  std::vector<NodeIndex> targets;
  for (int i = 0; i < 40 * repetitions; ++i) targets.push_back(any(rng));
  // The plain reverse Dijkstra over every node, then the default (core search, dead ends filled).
  const ExactSolver plain({.use_dead_ends = false});  // reuses its scratch space, as TravelPlanner does
  std::vector<double> full;
  for (NodeIndex t : targets)
    full.push_back(seconds_of([&] { g_sink = g_sink + plain.solve(mdp, t)->policy.expected_seconds(0); }));
  row("exact policy, reverse Dijkstra over every node", median(full), full.size());
  const ExactSolver solver;
  std::vector<double> exact;
  for (NodeIndex t : targets)
    exact.push_back(seconds_of([&] { g_sink = g_sink + solver.solve(mdp, t)->policy.expected_seconds(0); }));
  const double exact_median = median(exact);
  row("exact single-target policy (default: dead ends)", exact_median, exact.size());

  // Value iteration on a subset of the same targets: Jacobi (PRISM's value iteration, the
  // published system's solver) and Gauss-Seidel.
  for (const bool gauss_seidel : {false, true}) {
    std::vector<double> vi;
    std::size_t sweeps = 0;
    const std::size_t vi_runs = std::min<std::size_t>(targets.size(), static_cast<std::size_t>(4 * repetitions));
    for (std::size_t i = 0; i < vi_runs; ++i) {
      vi.push_back(seconds_of([&] {
        auto s = ValueIteration({.tolerance = 1e-6, .gauss_seidel = gauss_seidel}).solve(mdp, targets[i]);
        sweeps += s->sweeps;
        g_sink = g_sink + s->policy.expected_seconds(0);
      }));
    }
    const double vi_median = median(vi);
    row(fmt::format("value iteration 1e-6, {} ({} sweeps)", gauss_seidel ? "Gauss-Seidel" : "Jacobi", sweeps / vi_runs),
        vi_median, vi.size());
    fmt::print("{:<52} {:>13.0f}x\n", "  exact speed-up over it (ratio of medians)", vi_median / exact_median);
    fmt::print("{:<52} {:>13.0f}x\n", "  plain reverse Dijkstra's speed-up over it", vi_median / median(full));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 5;
  const std::string witham_dir = argc > 2 ? argv[2] : "../shared/data/witham_wharf";
  fmt::print("{:<52} {:>14} {:>8}\n", "measurement (thread CPU time)", "median", "samples");
  const map::TopoMap grid = testing::building_map({.rows = 25, .columns = 40, .seed = 1});
  solver_rows(grid, testing::daily_models(grid), "floor grid (building_map 25 x 40), daily models", repetitions);
  const map::TopoMap m = testing::corridor_building_map({});
  solver_rows(m, testing::daily_models(m), "corridor building (corridor_building_map), daily models", repetitions);
  if (const std::vector<double> rates = witham_success_rates(witham_dir); !rates.empty()) {
    solver_rows(m, witham_rate_models(m, rates),
                fmt::format("corridor building, p from the {} Witham Wharf edges' success rates", rates.size()),
                repetitions);
  }

  auto models = std::make_shared<FunctionEdgeModels>(testing::daily_models(m));
  const Time day = *parse_time("2014-09-02T00:00:00Z");
  const Time noon = day + hours(12);
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<NodeIndex> any(0, m.node_count() - 1);
  const Mdp mdp = Mdp::build(m, *models, noon);

  // Policy distribution along the route (the probability of arriving on time).
  const Policy policy = ExactSolver{}.solve(mdp, 0)->policy;
  std::vector<double> dist;
  for (int r = 0; r < 20 * repetitions; ++r) {
    const NodeIndex from = any(rng);
    dist.push_back(seconds_of([&] { g_sink = g_sink + policy.travel_time_distribution(from).quantile(0.9).upper; }));
  }
  row(fmt::format("travel-time distribution + q90 (route ~{} edges)", policy.route(m.node_count() - 1).size()),
      median(dist), dist.size());

  // The executor's grid (exec::TravelCache: 1024 cells over 16 x the expected time) against its
  // first quarter, computed alone (DistributionOptions::computed_cells); the q80 is the same.
  for (const std::size_t computed : {std::size_t{0}, std::size_t{256}}) {
    std::vector<double> times;
    for (int r = 0; r < 20 * repetitions; ++r) {
      const NodeIndex from = any(rng);
      const DistributionOptions options{.cells = 1024, .horizon_factor = 16.0, .computed_cells = computed};
      times.push_back(
          seconds_of([&] { g_sink = g_sink + policy.travel_time_distribution(from, options).quantile(0.8).upper; }));
    }
    row(computed == 0 ? "  q80 on 1024 cells, the whole grid" : "  q80 on 1024 cells, the first 256 computed",
        median(times), times.size());
  }

  // A 50 x 50 matrix for 96 quarter-hour slots, from a fresh oracle each time.
  std::vector<NodeIndex> places;
  for (int i = 0; i < 50; ++i) places.push_back(any(rng));
  std::vector<double> matrix;
  for (int r = 0; r < repetitions; ++r) {
    matrix.push_back(seconds_of([&] {
      TravelPlanner oracle(m, models, {.slot_width = minutes(15)});
      double sum = 0;
      for (int slot = 0; slot < 96; ++slot) {
        const Time t = day + minutes(15 * slot);
        for (NodeIndex a : places)
          for (NodeIndex b : places) sum += oracle.expected_seconds(a, b, t);
      }
      g_sink = g_sink + sum;
    }));
  }
  row("50 x 50 travel matrix x 96 slots (fresh oracle)", median(matrix), matrix.size());

  // Cached lookups: the same matrix again on a warm oracle (one slot).
  {
    TravelPlanner oracle(m, models, {.slot_width = minutes(15)});
    for (NodeIndex b : places) oracle.policy(b, noon);
    std::vector<double> warm;
    for (int r = 0; r < 20 * repetitions; ++r) {
      warm.push_back(seconds_of([&] {
        double sum = 0;
        for (NodeIndex a : places)
          for (NodeIndex b : places) sum += oracle.expected_seconds(a, b, noon);
        g_sink = g_sink + sum;
      }));
    }
    row("50 x 50 matrix, one slot, warm cache", median(warm), warm.size());
  }

  // Time-dependent queries (each edge read when reached), warm slot cache after the first.
  {
    TravelPlanner oracle(m, models, {.slot_width = minutes(15)});
    std::vector<double> td;
    for (int r = 0; r < 20 * repetitions; ++r) {
      const NodeIndex a = any(rng);
      const NodeIndex b = any(rng);
      const Time t = day + minutes(static_cast<int>(rng() % 1440));
      td.push_back(seconds_of([&] { g_sink = g_sink + oracle.time_dependent_expected_seconds(a, b, t); }));
    }
    row("time-dependent route, one pair (slot cache filling)", median(td), td.size());
  }
  return 0;
}
