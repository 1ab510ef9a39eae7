// What the background scheduler's copy of the edge models costs the clock's thread (issue 37 point
// 6): `rondo serve` hands its worker a copy of plan::LearnedEdgeModels whenever the models changed
// since the last reschedule (executor_background.cpp), so after every edge attempt. The snapshot
// (learn::EdgeModels) is shared by the copy; what is copied is each map edge's online state, its
// id and its index. Measured on the real Witham Wharf map and logs (the largest real deployment
// here): the models fitted on the whole log, read online, every edge observed once; then the
// median CPU time of one copy, beside two things the clock's thread does after every edge attempt
// anyway, measured in the same run: one online update (observe) and one single-target policy of
// the planner on the updated models (the navigation's re-plan after an edge).
//
//   cmake --build build --target bench_model_copy
//   build/bench/bench_model_copy [WITHAM_DIR] [REPETITIONS]   # default ../shared/data/witham_wharf, 2000
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bench_clock.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/edge_models.h"
#include "rondo/map/map_loader.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/travel_planner.h"

namespace {

using namespace rondo;
using bench::thread_seconds;

double median_of(int repetitions, const std::function<void()>& work) {
  std::vector<double> v;
  for (int i = 0; i < repetitions; ++i) {
    const double start = thread_seconds();
    work();
    v.push_back(thread_seconds() - start);
  }
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

volatile double g_sink = 0;

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "../shared/data/witham_wharf";
  const int repetitions = argc > 2 ? std::max(1, std::atoi(argv[2])) : 2000;
  auto map = map::load_map("examples/witham/map.yaml");
  auto log = read_witham_logs(dir);
  if (!map || !log) {
    fmt::print(stderr, "bench_model_copy: {}\n", !map ? map.error().message : log.error().message);
    return 2;
  }
  learn::EdgeModelsOptions options;
  options.episode.zone = *TimeZone::named("Europe/London");
  std::shared_ptr<const learn::EdgeModels> fitted = *learn::EdgeModels::fit(plan::edge_specs(*map), *log, options);
  auto models = std::make_shared<plan::LearnedEdgeModels>(*map, fitted, plan::DistancePriorOptions{},
                                                          plan::LearnedEdgeModels::Reading::kOnline);
  const Time at = log->back().start + hours(1);
  for (map::EdgeIndex e = 0; e < map->edge_count(); ++e)
    models->observe(e, {.start = at, .end = at + seconds(20), .seconds = 20, .success = true});
  plan::TravelPlanner planner(*map, models);

  const double copy = median_of(repetitions, [&] {
    auto copied = std::make_shared<const plan::LearnedEdgeModels>(*models);
    g_sink = g_sink + static_cast<double>(copied->version());
  });
  Time t = at + hours(1);
  map::EdgeIndex e = 0;
  const double observe = median_of(repetitions, [&] {
    t += seconds(30);
    e = (e + 1) % map->edge_count();
    models->observe(e, {.start = t, .end = t + seconds(20), .seconds = 20, .success = true});
  });
  map::NodeIndex target = 0;
  const double policy = median_of(repetitions / 10 + 1, [&] {
    t += seconds(30);
    e = (e + 1) % map->edge_count();
    models->observe(e, {.start = t, .end = t + seconds(20), .seconds = 20, .success = true});
    target = (target + 1) % map->node_count();
    g_sink = g_sink + static_cast<double>(planner.solve_policy(target, t).next_edge(0).value_or(0));
  });
  fmt::print("Witham Wharf: {} nodes, {} edges ({} with a model), {} attempts\n", map->node_count(),
             map->edge_count(), models->known_edge_count(), log->size());
  fmt::print("{:<62} {:>10.1f} us\n", "copy of the models for the worker (per reschedule)", copy * 1e6);
  fmt::print("{:<62} {:>10.1f} us\n", "one online update (after every edge attempt)", observe * 1e6);
  fmt::print("{:<62} {:>10.1f} us\n", "observe + one single-target policy (the re-plan after an edge)", policy * 1e6);
  fmt::print("copy / (observe + policy) = {:.3f}\n", copy / policy);
  return 0;
}
