// Tasks written as co-safe LTL (issue 41): the automaton's size for the example formulas,
// and, on the TSC care-home map (67 nodes, 232 edges) with daily-rhythm models, the time to plan
// a formula of three clauses on the product, the exact solver against value iteration on the
// same product (median of the runs, and their ratio). See docs/ltl.md.
//
//   cmake -S . -B build -G Ninja -DRONDO_BUILD_BENCH=ON && cmake --build build --target bench_ltl
//   build/bench/bench_ltl [repetitions] [MAP]   # default 21, ../shared/data/maps/tsc_1605.yaml
//
// Times are this thread's CPU time (the harness only; the libraries never read a clock).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "plan/random_map.h"
#include "rondo/ltl/automaton.h"
#include "rondo/ltl/parser.h"
#include "rondo/map/map_loader.h"
#include "rondo/plan/product_solver.h"
#include "rondo/plan/spec_planner.h"

namespace {

using namespace rondo;
using namespace rondo::plan;
using bench::median;
using bench::seconds_of;

std::string duration_text(double seconds) {
  return seconds < 1e-3 ? fmt::format("{:.1f} us", seconds * 1e6) : fmt::format("{:.3f} ms", seconds * 1e3);
}

volatile double g_sink = 0;

void automaton_sizes(int repetitions) {
  struct Example {
    const char* words;
    const char* formula;
  };
  const std::vector<Example> examples = {
      {"visit WayPoint5 and WayPoint7, in any order", "F WayPoint5 & F WayPoint7"},
      {"go to WayPoint3, then to WayPoint5 or WayPoint9", "F (WayPoint3 & F (WayPoint5 | WayPoint9))"},
      {"reach the Station without passing WayPoint12", "!WayPoint12 U Station"},
      {"east fire door, then west, never the kitchen corridor", "!Kitchen U (EastDoor & (!Kitchen U WestDoor))"},
      {"the benchmark's three clauses", "F WayPoint5 & F WayPoint40 & !WayPoint12 U Station"},
      {"visit 8 places in any order", "F p1 & F p2 & F p3 & F p4 & F p5 & F p6 & F p7 & F p8"},
  };
  fmt::print("Automaton sizes (explored progressed formulas -> minimal states; letters; build time, median)\n");
  fmt::print("{:<56} {:>8} {:>8} {:>8} {:>12}\n", "formula", "explored", "states", "letters", "build");
  for (const Example& e : examples) {
    const ltl::Formula f = ltl::parse_formula(e.formula).value();
    std::vector<double> times;
    std::size_t explored = 0, states = 0, letters = 0;
    for (int r = 0; r < repetitions; ++r)
      times.push_back(seconds_of([&] {
        const ltl::Automaton a = ltl::Automaton::build(f).value();
        explored = a.explored_states(), states = a.state_count(), letters = a.letter_count();
      }));
    fmt::print("{:<56} {:>8} {:>8} {:>8} {:>12}\n", e.words, explored, states, letters, duration_text(median(times)));
  }
}

void plan_on_map(const map::TopoMap& map, int repetitions) {
  const char* formula = "F WayPoint5 & F WayPoint40 & !WayPoint12 U Station";
  auto automaton = std::make_shared<const ltl::Automaton>(
      ltl::Automaton::build(ltl::parse_formula(formula).value()).value());
  const FunctionEdgeModels models = testing::daily_models(map);
  const NodeIndex start = *map.find_node("ChargingPoint");
  std::vector<double> exact_times, vi_times, vi_tight_times, build_times, plan_times;
  std::size_t sweeps = 0, tight_sweeps = 0;
  auto shared_models = std::make_shared<const FunctionEdgeModels>(models);
  const SpecPlanner planner = SpecPlanner::create(map, shared_models, automaton).value();
  double worst_gap = 0.0, eta = 0.0;
  for (int r = 0; r < repetitions; ++r) {
    const Time at = from_unix_seconds(1.4e9 + 3600.0 * r);  // a different hour each run
    const Mdp mdp = Mdp::build(map, models, at);
    build_times.push_back(seconds_of([&] { g_sink = static_cast<double>(ProductMdp::build(mdp, automaton)->state_count()); }));
    const ProductMdp product = ProductMdp::build(mdp, automaton).value();
    const auto q = product.start_state(start);
    ProductSolution exact = ProductExactSolver{}.solve(product);
    exact_times.push_back(seconds_of([&] { exact = ProductExactSolver{}.solve(product); }));
    ProductSolution vi = ProductValueIteration({.tolerance = 1e-6}).solve(product);
    vi_times.push_back(seconds_of([&] { vi = ProductValueIteration({.tolerance = 1e-6}).solve(product); }));
    sweeps = vi.sweeps;
    vi_tight_times.push_back(seconds_of([&] { vi = ProductValueIteration({.tolerance = 1e-9}).solve(product); }));
    tight_sweeps = vi.sweeps;
    plan_times.push_back(seconds_of([&] { g_sink = planner.plan(start, q, at)->expected_seconds(); }));
    eta = exact.policy.expected_seconds(start, q);
    const double v = vi.policy.expected_seconds(start, q);
    worst_gap = std::max(worst_gap, std::abs(v - eta) / eta);
  }
  fmt::print("\nPlanning '{}' on {} ({} nodes, {} edges) from ChargingPoint, {} departure hours\n", formula,
             map.name(), map.node_count(), map.edge_count(), repetitions);
  fmt::print("product: {} nodes x {} automaton states = {} states; expected time of the last run {:.1f} s\n",
             map.node_count(), automaton->state_count(), map.node_count() * automaton->state_count(), eta);
  fmt::print("{:<52} {:>14}\n", "product build (median)", duration_text(median(build_times)));
  fmt::print("{:<52} {:>14}\n", "exact solver (median)", duration_text(median(exact_times)));
  fmt::print("{:<52} {:>14}\n", fmt::format("value iteration, tolerance 1e-6 ({} sweeps)", sweeps).c_str(),
             duration_text(median(vi_times)));
  fmt::print("{:<52} {:>14}\n", fmt::format("value iteration, tolerance 1e-9 ({} sweeps)", tight_sweeps).c_str(),
             duration_text(median(vi_tight_times)));
  fmt::print("{:<52} {:>13.1f}x\n", "value iteration 1e-6 / exact (ratio of medians)", median(vi_times) / median(exact_times));
  fmt::print("{:<52} {:>13.1f}x\n", "value iteration 1e-9 / exact (ratio of medians)",
             median(vi_tight_times) / median(exact_times));
  fmt::print("{:<52} {:>14}\n", "SpecPlanner::plan: M_t + product + exact (median)", duration_text(median(plan_times)));
  fmt::print("{:<52} {:>14.2e}\n", "largest relative gap of the start's expected time", worst_gap);
}

}  // namespace

int main(int argc, char** argv) {
  const int repetitions = argc > 1 ? std::max(1, std::atoi(argv[1])) : 21;
  const std::string path = argc > 2 ? argv[2] : "../shared/data/maps/tsc_1605.yaml";
  fmt::print("load average: {}\n\n", bench::load_average());
  automaton_sizes(repetitions);
  const Result<map::TopoMap> map = map::load_map(path);
  if (!map) {
    fmt::print(stderr, "{}\n", map.error().message);
    return 2;
  }
  plan_on_map(*map, repetitions);
  return 0;
}
