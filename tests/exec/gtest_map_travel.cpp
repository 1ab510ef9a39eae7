// Properties of the scheduler's travel over the planner (exec::SchedulerTravel): FIFO, the lower bound,
// agreement with the planner at slot starts, and cache invalidation when the models change.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <memory>

#include "plan/patchable_models.h"
#include "rondo/exec/map_travel.h"
#include "rondo/plan/edge_model_view.h"
#include "rondo/plan/travel_planner.h"
#include "scenario.h"

namespace rondo::exec::testing {
namespace {

const Time kMonday = from_unix_seconds(1'795'392'000);  // 2026-11-23T00:00Z

// Edge outcomes that change with the time of day (a daily rhythm, so weekly periodic too): each
// edge has its own phase, amplitude and success probability.
std::shared_ptr<plan::FunctionEdgeModels> rhythmic_models(std::vector<double> phase, double amplitude, double p) {
  return std::make_shared<plan::FunctionEdgeModels>([=](map::EdgeIndex e, Time t) {
    const double hour = std::fmod(to_seconds(t.time_since_epoch()) / 3600.0, 24.0);
    const double wave = 1.0 + amplitude * (1.0 + std::sin((hour + phase[e % phase.size()]) * M_PI / 12.0));
    return plan::EdgeOutcome{p, 20.0 * wave};
  });
}

RC_GTEST_PROP(SchedulerTravel, IsFifoAndAboveItsLowerBound, ()) {
  const map::TopoMap map = scenario_map();
  const auto phase = *rc::gen::container<std::vector<double>>(map.edge_count(), rc::gen::inRange(0, 24));
  const double amplitude = *rc::gen::inRange(0, 40) / 10.0;
  const double p = *rc::gen::inRange(30, 101) / 100.0;
  auto models = rhythmic_models(phase, amplitude, p);
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  SchedulerTravel travel(cache, {0, 1, 2, 3, 4});
  const auto a = *rc::gen::inRange<std::size_t>(0, 5);
  const auto b = *rc::gen::inRange<std::size_t>(0, 5);
  const Time t1 = kMonday + seconds(*rc::gen::inRange(0, 7 * 86400));
  const Time t2 = t1 + seconds(*rc::gen::inRange(0, 4 * 3600));
  const Duration d1 = travel.travel(a, b, t1), d2 = travel.travel(a, b, t2);
  RC_ASSERT(t1 + d1 <= t2 + d2 + Duration{1});  // FIFO (1 ms of rounding)
  RC_ASSERT(travel.lower_bound(a, b) <= d1);
  RC_ASSERT(travel.lower_bound(a, b) <= d2);
  RC_ASSERT(d1 >= Duration{0});
}

RC_GTEST_PROP(SchedulerQuantileTravel, IsFifoAndGrowsWithTheLevel, ()) {
  const map::TopoMap map = scenario_map();
  const auto phase = *rc::gen::container<std::vector<double>>(map.edge_count(), rc::gen::inRange(0, 24));
  const double p = *rc::gen::inRange(30, 101) / 100.0;
  auto models = rhythmic_models(phase, *rc::gen::inRange(0, 40) / 10.0, p);
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  const double level = *rc::gen::inRange(50, 99) / 100.0;
  SchedulerQuantileTravel q(cache, {0, 1, 2, 3, 4}, level);
  SchedulerQuantileTravel higher(cache, {0, 1, 2, 3, 4}, std::min(0.99, level + 0.05));
  const auto a = *rc::gen::inRange<std::size_t>(0, 5);
  const auto b = *rc::gen::inRange<std::size_t>(0, 5);
  const Time t1 = kMonday + seconds(*rc::gen::inRange(0, 7 * 86400));
  const Time t2 = t1 + seconds(*rc::gen::inRange(0, 4 * 3600));
  const Duration d1 = q.travel(a, b, t1), d2 = q.travel(a, b, t2);
  RC_ASSERT(t1 + d1 <= t2 + d2 + Duration{1});  // FIFO (1 ms of rounding)
  RC_ASSERT(d1 >= Duration{0});
  RC_ASSERT(higher.travel(a, b, t1) >= d1);
}

TEST(SchedulerQuantileTravel, IsTheRoutesDistributionQuantileAtSlotStarts) {
  const map::TopoMap map = scenario_map();
  auto models = std::make_shared<plan::FunctionEdgeModels>(
      [](map::EdgeIndex, Time) { return plan::EdgeOutcome{0.5, 10.0}; });
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  const map::NodeIndex dock = *map.find_node("Dock"), office = *map.find_node("Office");
  const Time s0 = kMonday + hours(9);
  // Two edges of 10 s, each tried until it succeeds with p = 0.5: T = 10 s × (N1 + N2), N geometric.
  // P(T <= 40 s) = P(N1 + N2 <= 4) = 1 − P(more than 4) = 1 − 5/16 = 0.6875; P(<= 50 s) = 0.8125.
  const Duration q = cache.quantile_at_slot(dock, office, s0, 0.8);
  EXPECT_GE(q, seconds(50));
  EXPECT_LE(q, seconds(51));  // the grid's bracket
  EXPECT_EQ(cache.travel(dock, office, s0), seconds(40));  // the expected value stays
  EXPECT_EQ(cache.quantile_at_slot(dock, dock, s0, 0.8), Duration{0});
}

TEST(SchedulerTravel, EqualsThePlannerAtSlotStartsAndInterpolatesBetween) {
  const map::TopoMap map = scenario_map();
  auto models = rhythmic_models({0, 3, 6, 9, 12, 15, 18, 21}, 1.5, 0.8);
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  const map::NodeIndex dock = *map.find_node("Dock"), office = *map.find_node("Office");
  SchedulerTravel travel(cache, {dock, office});
  const Time s0 = kMonday + hours(9), s1 = s0 + minutes(15);
  const double e0 = planner.expected_seconds(dock, office, s0), e1 = planner.expected_seconds(dock, office, s1);
  EXPECT_NEAR(to_seconds(travel.travel(0, 1, s0)), e0, 0.001);
  EXPECT_NEAR(to_seconds(travel.travel(0, 1, s1)), e1, 0.001);
  EXPECT_NEAR(to_seconds(travel.travel(0, 1, s0 + minutes(5))), e0 + (e1 - e0) / 3.0, 0.002);
  EXPECT_EQ(travel.travel(0, 0, s0), Duration{0});
}

TEST(SchedulerTravel, NewModelsEmptyTheCache) {
  const map::TopoMap map = scenario_map();
  auto models = std::make_shared<plan::FunctionEdgeModels>(
      [](map::EdgeIndex, Time) { return plan::EdgeOutcome{1.0, 10.0}; });
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  SchedulerTravel travel(cache, {*map.find_node("Dock"), *map.find_node("Office")});
  EXPECT_EQ(travel.travel(0, 1, kMonday), seconds(20));
  EXPECT_EQ(travel.lower_bound(0, 1), seconds(20));
  models->set([](map::EdgeIndex, Time) { return plan::EdgeOutcome{0.5, 10.0}; });
  EXPECT_EQ(travel.travel(0, 1, kMonday), seconds(40));
  EXPECT_EQ(travel.lower_bound(0, 1), seconds(40));
}

// After any sequence of one-edge updates (and snapshot swaps), every cached travel time and lower
// bound equals what a fresh cache over a fresh planner gives: the entries kept were untouched.
RC_GTEST_PROP(SchedulerTravel, CachedAnswersEqualAFreshCacheAfterOneEdgeUpdates, ()) {
  const map::TopoMap map = scenario_map();
  const auto phase = *rc::gen::container<std::vector<double>>(map.edge_count(), rc::gen::inRange(0, 24));
  auto base = rhythmic_models(phase, 1.5, 0.8);
  auto models = std::make_shared<plan::testing::PatchableEdgeModels>(
      map.edge_count(), [base](map::EdgeIndex e, Time t) { return base->outcome(e, t); });
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  const int steps = *rc::gen::inRange(1, 40);
  for (int k = 0; k < steps; ++k) {
    const int what = *rc::gen::inRange(0, 10);
    if (what < 3) {
      models->change(*rc::gen::inRange<std::size_t>(0, map.edge_count()), *rc::gen::element(1.0, 0.5, 0.0),
                     *rc::gen::element(1.0, 0.25, 3.0));
    } else if (what == 3) {
      models->change_all(*rc::gen::element(1.0, 0.8), 1.0);
    } else {
      const auto a = *rc::gen::inRange<std::size_t>(0, map.node_count());
      const auto b = *rc::gen::inRange<std::size_t>(0, map.node_count());
      const Time t = kMonday + hours(9) + seconds(*rc::gen::inRange(0, 3 * 3600));
      plan::TravelPlanner fresh_planner(map, models, {.slot_width = minutes(15)});
      TravelCache fresh(map, models, fresh_planner, minutes(15));
      RC_ASSERT(cache.travel(a, b, t) == fresh.travel(a, b, t));
      RC_ASSERT(cache.lower_bound(a, b) == fresh.lower_bound(a, b));
    }
  }
}

TEST(SchedulerTravel, AnUpdateOfAnEdgeOffTheWayKeepsTheEntry) {
  const map::TopoMap map = scenario_map();
  auto models = std::make_shared<plan::testing::PatchableEdgeModels>(map.edge_count(), [](map::EdgeIndex, Time) {
    return plan::EdgeOutcome{1.0, 10.0};
  });
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  const map::NodeIndex dock = *map.find_node("Dock"), office = *map.find_node("Office");
  const Duration before = cache.travel(dock, office, kMonday);
  // Slower edges that no route to the office takes: into the dock.
  for (map::EdgeIndex e : map.in_edges(dock)) models->change(e, 1.0, 2.0);
  EXPECT_EQ(cache.travel(dock, office, kMonday), before);
  EXPECT_EQ(cache.resolved_count(), 0u);
  EXPECT_GT(cache.kept_count(), 0u);
}

TEST(SchedulerTravel, AnUnreachableNodeIsKUnreachable) {
  const map::TopoMap map = scenario_map();
  auto models = std::make_shared<plan::FunctionEdgeModels>([&](map::EdgeIndex e, Time) {
    return plan::EdgeOutcome{map.edge(e).to == "Lab" ? 0.0 : 1.0, 10.0};
  });
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  SchedulerTravel travel(cache, {*map.find_node("Dock"), *map.find_node("Lab")});
  EXPECT_EQ(travel.travel(0, 1, kMonday), kUnreachable);
  EXPECT_EQ(travel.lower_bound(0, 1), kUnreachable);
}

}  // namespace
}  // namespace rondo::exec::testing
