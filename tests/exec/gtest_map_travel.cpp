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
    return plan::EdgeCrossing{p, 20.0 * wave};
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
      [](map::EdgeIndex, Time) { return plan::EdgeCrossing{0.5, 10.0}; });
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
      [](map::EdgeIndex, Time) { return plan::EdgeCrossing{1.0, 10.0}; });
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  SchedulerTravel travel(cache, {*map.find_node("Dock"), *map.find_node("Office")});
  EXPECT_EQ(travel.travel(0, 1, kMonday), seconds(20));
  EXPECT_EQ(travel.lower_bound(0, 1), seconds(20));
  models->set([](map::EdgeIndex, Time) { return plan::EdgeCrossing{0.5, 10.0}; });
  EXPECT_EQ(travel.travel(0, 1, kMonday), seconds(40));
  EXPECT_EQ(travel.lower_bound(0, 1), seconds(40));
}

// Daily rhythms with random phases (a generated property input), each edge patchable after.
std::shared_ptr<plan::testing::PatchableEdgeModels> patchable_rhythmic_models(const map::TopoMap& map) {
  const auto phase = *rc::gen::container<std::vector<double>>(map.edge_count(), rc::gen::inRange(0, 24));
  auto base = rhythmic_models(phase, 1.5, 0.8);
  return std::make_shared<plan::testing::PatchableEdgeModels>(
      map.edge_count(), [base](map::EdgeIndex e, Time t) { return base->outcome(e, t); });
}

// After any sequence of one-edge updates (and snapshot swaps), every cached travel time and lower
// bound equals what a fresh cache over a fresh planner gives: the entries kept were untouched.
RC_GTEST_PROP(SchedulerTravel, CachedAnswersEqualAFreshCacheAfterOneEdgeUpdates, ()) {
  const map::TopoMap map = scenario_map();
  auto models = patchable_rhythmic_models(map);
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

// A problem's oracles keep the values they read (SlotTable): whatever the order of the reads
// (earlier slots after later ones too) and the updates between them, each answer equals the
// cache's, read directly.
RC_GTEST_PROP(SchedulerTravel, ItsTableAnswersAsTheCacheDoes, ()) {
  const map::TopoMap map = scenario_map();
  auto models = patchable_rhythmic_models(map);
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  const std::vector<map::NodeIndex> nodes{0, 1, 2, 3, 4, 2};  // two locations on one node
  SchedulerTravel travel(cache, nodes);
  SchedulerQuantileTravel quantile(cache, nodes, 0.9);
  const int steps = *rc::gen::inRange(1, 60);
  for (int k = 0; k < steps; ++k) {
    if (*rc::gen::inRange(0, 10) == 0) {
      models->change(*rc::gen::inRange<std::size_t>(0, map.edge_count()), *rc::gen::element(1.0, 0.5, 0.0),
                     *rc::gen::element(1.0, 0.25, 3.0));
      continue;
    }
    const auto a = *rc::gen::inRange<std::size_t>(0, nodes.size());
    const auto b = *rc::gen::inRange<std::size_t>(0, nodes.size());
    const Time t = kMonday + hours(9) + seconds(*rc::gen::inRange(0, 3 * 3600));
    RC_ASSERT(travel.travel(a, b, t) == cache.travel(nodes[a], nodes[b], t));
    RC_ASSERT(quantile.travel(a, b, t) == cache.quantile_travel(nodes[a], nodes[b], t, 0.9));
  }
}

TEST(SchedulerTravel, AnUpdateOfAnEdgeOffTheWayKeepsTheEntry) {
  const map::TopoMap map = scenario_map();
  auto models = std::make_shared<plan::testing::PatchableEdgeModels>(map.edge_count(), [](map::EdgeIndex, Time) {
    return plan::EdgeCrossing{1.0, 10.0};
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
    return plan::EdgeCrossing{map.edge(e).to == "Lab" ? 0.0 : 1.0, 10.0};
  });
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  SchedulerTravel travel(cache, {*map.find_node("Dock"), *map.find_node("Lab")});
  EXPECT_EQ(travel.travel(0, 1, kMonday), kUnreachable);
  EXPECT_EQ(travel.lower_bound(0, 1), kUnreachable);
}

// Asks `travel` for every pair of its locations at every slot start in [from, from + span).
void ask_all(const SchedulerTravel& travel, Time from, Duration span) {
  for (Time t = from; t < from + span; t += minutes(15))
    for (std::size_t a = 0; a < travel.location_count(); ++a)
      for (std::size_t b = 0; b < travel.location_count(); ++b) (void)travel.travel(a, b, t);
}

TEST(SchedulerTravel, TheCountBoundEvictsWhatRecentProblemsDidNotRead) {
  const map::TopoMap map = scenario_map();
  auto models = rhythmic_models({0, 3, 6, 9, 12, 15, 18, 21}, 1.5, 0.8);
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  const std::vector<map::NodeIndex> all = {0, 1, 2, 3, 4};
  // A day's problem to every node: 5 targets x 97 slot starts, far above the floor.
  {
    SchedulerTravel day(cache, all);
    ask_all(day, kMonday, hours(24) - minutes(15));
  }
  const std::size_t day_entries = cache.cached_count();
  EXPECT_GT(day_entries, kTravelCacheFloor);
  // Small problems after it: the day's entries stay while the day is among the recent working
  // sets (the bound is twice its size) ...
  const std::vector<map::NodeIndex> two = {*map.find_node("Dock"), *map.find_node("Office")};
  for (int k = 0; k < 7; ++k) {
    SchedulerTravel small(cache, two);
    ask_all(small, kMonday + hours(20), hours(1));
  }
  EXPECT_EQ(cache.evicted_count(), 0u);
  EXPECT_EQ(cache.cached_count(), day_entries);
  // ... and go, least recently read first, once it is not: down to the floor.
  const std::size_t solved = cache.solved_count();
  SchedulerTravel next(cache, two);
  EXPECT_EQ(cache.cached_count(), kTravelCacheFloor);
  EXPECT_EQ(cache.evicted_count(), day_entries - kTravelCacheFloor);
  // The previous problem's entries are still there: asking them again solves nothing.
  ask_all(next, kMonday + hours(20), hours(1));
  EXPECT_EQ(cache.solved_count(), solved);
  // And what was evicted is solved again, equal to what a fresh cache gives.
  plan::TravelPlanner fresh_planner(map, models, {.slot_width = minutes(15)});
  TravelCache fresh(map, models, fresh_planner, minutes(15));
  for (map::NodeIndex a : all)
    for (map::NodeIndex b : all) EXPECT_EQ(cache.travel(a, b, kMonday + hours(8)), fresh.travel(a, b, kMonday + hours(8)));
  EXPECT_GT(cache.solved_count(), solved);
}

// However problems come (any nodes, any hours of two days), answers equal a fresh cache's, the
// count stays within its bound after each problem opens, and the previous problem's entries are
// never solved again when the next problem asks for them.
RC_GTEST_PROP(SchedulerTravel, TheCountBoundKeepsAnswersAndThePreviousProblem, ()) {
  const map::TopoMap map = scenario_map();
  const auto phase = *rc::gen::container<std::vector<double>>(map.edge_count(), rc::gen::inRange(0, 24));
  auto models = rhythmic_models(phase, 1.5, 0.8);
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15));
  const int problems = *rc::gen::inRange(1, 30);
  Time start = kMonday;
  std::vector<map::NodeIndex> previous_nodes;
  Time previous_from = start;
  Duration previous_span{0};
  for (int k = 0; k < problems; ++k) {
    const auto chosen = *rc::gen::container<std::vector<bool>>(map.node_count(), rc::gen::arbitrary<bool>());
    std::vector<map::NodeIndex> nodes;
    for (map::NodeIndex n = 0; n < map.node_count(); ++n)
      if (chosen[n]) nodes.push_back(n);
    start += minutes(15) * *rc::gen::inRange(0, 8);  // departures move forward
    const Duration span = hours(*rc::gen::inRange(1, 24));
    SchedulerTravel travel(cache, nodes);
    RC_ASSERT(cache.cached_count() <= std::max(kTravelCacheFloor, kTravelCacheWorkingSets * 5 * 97));
    if (!previous_nodes.empty() && *rc::gen::arbitrary<bool>()) {
      const std::size_t solved = cache.solved_count();
      ask_all(SchedulerTravel(cache, previous_nodes), previous_from, previous_span);
      RC_ASSERT(cache.solved_count() == solved);
    }
    ask_all(travel, start, span);
    previous_nodes = nodes;
    previous_from = start;
    previous_span = span;
  }
  RC_CLASSIFY(cache.evicted_count() > 0, "evicted");
  plan::TravelPlanner fresh_planner(map, models, {.slot_width = minutes(15)});
  TravelCache fresh(map, models, fresh_planner, minutes(15));
  for (map::NodeIndex a = 0; a < map.node_count(); ++a)
    for (map::NodeIndex b = 0; b < map.node_count(); ++b)
      RC_ASSERT(cache.travel(a, b, start + minutes(7)) == fresh.travel(a, b, start + minutes(7)));
}

}  // namespace
}  // namespace rondo::exec::testing
