// What an online update of one edge costs the executor's caches (issue 15, point 6): the
// scheduler's travel matrix (exec::TravelCache over plan::TravelPlanner) for `targets` places and
// the 96 quarter-hour slots of a day is filled, then, again and again, one edge is updated (as
// LearnedEdgeModels::observe does after an attempt) and the whole matrix read again. Two views of
// the same models: one that names the changed edge (changed_since: entries it does not touch are
// kept) and one that cannot (every update empties the caches, the behaviour before). Prints the
// median CPU time per update + re-read and the share of cached policies kept. The updated edges
// are random edges of the map (most are off most routes) and, separately, edges on a route the
// matrix uses (the robot's own edges: the worst case).
//
//   cmake -S . -B build -G Ninja -DRONDO_BUILD_BENCH=ON && cmake --build build --target bench_live_update
//   build/bench/bench_live_update [updates]      # default 20
#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <random>
#include <vector>

#include "plan/patchable_models.h"
#include "plan/random_map.h"
#include "bench_clock.h"
#include "rondo/exec/map_travel.h"
#include "rondo/plan/travel_planner.h"

namespace {

using namespace rondo;
using bench::median;
using bench::thread_seconds;

// The same models, but unable to say which edges changed: caches must assume everything did.
class Opaque final : public plan::EdgeModelView {
 public:
  explicit Opaque(std::shared_ptr<const plan::EdgeModelView> inner) : inner_(std::move(inner)) {}
  plan::EdgeCrossing outcome(map::EdgeIndex e, Time t) const override { return inner_->outcome(e, t); }
  std::uint64_t version() const override { return inner_->version(); }

 private:
  std::shared_ptr<const plan::EdgeModelView> inner_;
};

volatile double g_sink = 0;

struct Measured {
  double seconds = 0;   // median per update + re-read
  double resolved = 0;  // cached (slot, target) entries solved again per update (of 96 x 12)
};

Measured run(const map::TopoMap& m, bool name_edges, bool on_route, int updates) {
  const plan::FunctionEdgeModels daily = plan::testing::daily_models(m);
  auto models = std::make_shared<plan::testing::PatchableEdgeModels>(
      m.edge_count(), [daily](map::EdgeIndex e, Time t) { return daily.outcome(e, t); });
  std::shared_ptr<const plan::EdgeModelView> view =
      name_edges ? std::shared_ptr<const plan::EdgeModelView>(models) : std::make_shared<Opaque>(models);
  plan::TravelPlanner planner(m, view, {.slot_width = minutes(15), .max_cached_policies = 4096});
  exec::TravelCache cache(m, view, planner, minutes(15));
  std::mt19937_64 rng(7);
  std::vector<map::NodeIndex> places;
  for (std::size_t k = 0; k < 12; ++k) places.push_back(rng() % m.node_count());
  const Time day = Time{} + hours(24 * 20000);
  auto read_matrix = [&] {
    double sum = 0;
    for (int s = 0; s < 96; ++s)
      for (map::NodeIndex a : places)
        for (map::NodeIndex b : places) sum += to_seconds(cache.at_slot(a, b, day + minutes(15 * s)));
    g_sink = sum;
  };
  read_matrix();
  std::vector<double> times;
  for (int u = 0; u < updates; ++u) {
    map::EdgeIndex e = rng() % m.edge_count();
    if (on_route) {
      const plan::Policy& p = planner.policy(places[1], day + minutes(15 * (u % 96)));
      e = p.next_edge(places[0]).value_or(e);
    }
    const double start = thread_seconds();
    models->change(e, u % 2 == 0 ? 0.5 : 1.0, u % 2 == 0 ? 1.5 : 1.0);
    read_matrix();
    times.push_back(thread_seconds() - start);
  }
  return {median(times), static_cast<double>(cache.resolved_count()) / updates};
}

}  // namespace

int main(int argc, char** argv) {
  const int updates = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  const map::TopoMap m = plan::testing::corridor_building_map({.floors = 2});
  fmt::print("map: {} places, {} edges; 12 x 12 travel matrix over 96 slots; {} updates\n", m.node_count(),
             m.edge_count(), updates);
  fmt::print("{:<40} {:>16} {:>14}\n", "updated edge / caches", "per update", "re-solved");
  for (const bool on_route : {false, true}) {
    for (const bool name_edges : {true, false}) {
      const Measured r = run(m, name_edges, on_route, updates);
      fmt::print(
          "{:<40} {:>13.2f} ms {:>8.1f} / 1152\n",
          fmt::format("{} / {}", on_route ? "on a route" : "random edge", name_edges ? "keep untouched" : "empty all"),
          r.seconds * 1e3, r.resolved);
    }
  }
  return 0;
}
