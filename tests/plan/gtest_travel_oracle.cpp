// TravelPlanner: E(a, b, t) matches the exact solver on M_t at the slot start, is cached per
// (slot, target), and is dropped when the models' version moves on; the time-dependent variant
// reads each edge when the robot reaches it, waits when waiting pays, and is FIFO (a property on
// random maps with daily-rhythm models).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <memory>
#include <vector>

#include "random_map.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/travel_planner.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

using testing::small_map;

const Time kMorning = Time{} + hours(24 * 16000 + 8);  // 2013-10-23T08:00:00Z

TEST(TravelPlanner, MatchesTheExactSolverAtTheSlotStart) {
  const map::TopoMap m = testing::building_map({.rows = 6, .columns = 7});
  auto models = std::make_shared<FunctionEdgeModels>(testing::daily_models(m));
  TravelPlanner oracle(m, models, {.slot_width = minutes(30)});
  const Time depart = kMorning + minutes(47);
  EXPECT_EQ(oracle.slot_start(depart), kMorning + minutes(30));
  const Mdp mdp = Mdp::build(m, *models, kMorning + minutes(30));
  const Policy truth = ExactSolver{}.solve(mdp, 5).value().policy;
  for (NodeIndex a = 0; a < m.node_count(); ++a)
    EXPECT_EQ(oracle.expected_seconds(a, 5, depart), truth.expected_seconds(a));
  EXPECT_EQ(oracle.expected_seconds(3, 3, depart), 0.0);
  EXPECT_THROW(oracle.expected_seconds(0, 999, depart), std::out_of_range);
}

TEST(TravelPlanner, CachesPerSlotAndTarget) {
  const map::TopoMap m = testing::building_map({.rows = 4, .columns = 4});
  auto models = std::make_shared<FunctionEdgeModels>(testing::daily_models(m));
  TravelPlanner oracle(m, models, {.slot_width = minutes(15)});
  oracle.expected_seconds(0, 5, kMorning);
  oracle.expected_seconds(1, 5, kMorning + minutes(14));  // same slot, same target
  EXPECT_EQ(oracle.cached_policy_count(), 1u);
  oracle.expected_seconds(0, 6, kMorning);
  oracle.expected_seconds(0, 5, kMorning + minutes(15));
  EXPECT_EQ(oracle.cached_policy_count(), 3u);
  EXPECT_EQ(oracle.cached_slot_count(), 2u);
}

TEST(TravelPlanner, ModelChangesInvalidateTheCache) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B"});
  auto models = std::make_shared<FunctionEdgeModels>([](map::EdgeIndex, Time) { return EdgeCrossing{1.0, 10.0}; });
  TravelPlanner oracle(m, models);
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 1, kMorning), 10.0);
  models->set([](map::EdgeIndex, Time) { return EdgeCrossing{0.5, 10.0}; });
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 1, kMorning), 20.0);
  EXPECT_EQ(oracle.cached_policy_count(), 1u);
}

TEST(TravelPlanner, CacheLimitsHold) {
  const map::TopoMap m = testing::building_map({.rows = 3, .columns = 3});
  auto models = std::make_shared<FunctionEdgeModels>(testing::daily_models(m));
  TravelPlanner oracle(m, models, {.max_cached_policies = 4, .max_cached_slots = 2});
  for (int k = 0; k < 20; ++k) oracle.expected_seconds(0, 8, kMorning + minutes(15 * k));
  EXPECT_LE(oracle.cached_policy_count(), 4u);
  EXPECT_LE(oracle.cached_slot_count(), 2u);
}

TEST(TimeDependent, EqualsTheStaticAnswerWhenModelsIgnoreTime) {
  const map::TopoMap m = testing::building_map({.rows = 5, .columns = 5});
  auto prior = std::make_shared<DistancePrior>(m, DistancePriorOptions{.success_probability = 0.8});
  TravelPlanner oracle(m, prior);
  for (NodeIndex a : {0u, 7u, 13u}) {
    const TimedRoute r = oracle.time_dependent_route(a, 24, kMorning);
    ASSERT_TRUE(r.reachable);
    EXPECT_NEAR(r.arrival_seconds, oracle.expected_seconds(a, 24, kMorning), 1e-9);
    ASSERT_FALSE(r.steps.empty());
    EXPECT_EQ(r.steps.front().from, a);
    EXPECT_EQ(r.steps.back().to, 24u);
  }
}

// A>B takes 600 s; B>C takes 60 s before 08:10 and 300 s from 08:10. Leaving A at 08:00, the robot
// reaches B at 08:10: the time-dependent answer reads B>C then, the static one at 08:00.
TEST(TimeDependent, ReadsEachEdgeWhenTheRobotReachesIt) {
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "B>C"});
  auto models = std::make_shared<FunctionEdgeModels>([](map::EdgeIndex e, Time t) {
    if (e == 0) return EdgeCrossing{1.0, 600.0};
    return EdgeCrossing{1.0, t < kMorning + minutes(10) ? 60.0 : 300.0};
  });
  TravelPlanner oracle(m, models, {.slot_width = minutes(5)});
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 2, kMorning), 660.0);
  const TimedRoute r = oracle.time_dependent_route(0, 2, kMorning);
  EXPECT_DOUBLE_EQ(r.arrival_seconds, 900.0);
  ASSERT_EQ(r.steps.size(), 2u);
  EXPECT_DOUBLE_EQ(r.steps[1].reach_seconds, 600.0);
}

TEST(TimeDependent, WaitsForAClosedDoorWhenThatIsFastest) {
  // A>B is closed until 08:15; the detour A>C>B takes an hour.
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "A>C", "C>B"});
  auto models = std::make_shared<FunctionEdgeModels>([](map::EdgeIndex e, Time t) {
    if (e == 0) return EdgeCrossing{t < kMorning + minutes(15) ? 0.0 : 1.0, 20.0};
    return EdgeCrossing{1.0, 1800.0};
  });
  TravelPlanner oracle(m, models, {.slot_width = minutes(15)});
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 1, kMorning), 3600.0);  // static: the detour
  const TimedRoute r = oracle.time_dependent_route(0, 1, kMorning + minutes(5));
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_DOUBLE_EQ(r.steps[0].start_seconds, 600.0);  // waits 10 min for the door
  EXPECT_DOUBLE_EQ(r.arrival_seconds, 620.0);
}

TEST(TimeDependent, UnreachableIsInfinite) {
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B"});
  auto prior = std::make_shared<DistancePrior>(m);
  TravelPlanner oracle(m, prior);
  EXPECT_FALSE(oracle.time_dependent_route(0, 2, kMorning).reachable);
  EXPECT_EQ(oracle.time_dependent_expected_seconds(1, 0, kMorning), kInfinity);
  EXPECT_EQ(oracle.time_dependent_expected_seconds(2, 2, kMorning), 0.0);
}

RC_GTEST_PROP(TimeDependentProperties, LeavingLaterNeverArrivesEarlier, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const map::TopoMap m = testing::building_map({.rows = 5, .columns = 6, .seed = seed, .door_fraction = 0.4});
  // Strong rhythms and 10-minute slots make the raw edge costs jump at every slot boundary.
  auto models = std::make_shared<FunctionEdgeModels>(testing::daily_models(m, 60.0));
  TravelPlanner oracle(m, models, {.slot_width = minutes(10)});
  const NodeIndex a = *rc::gen::inRange<std::size_t>(0, m.node_count());
  const NodeIndex b = *rc::gen::inRange<std::size_t>(0, m.node_count());
  const Time t1 = kMorning + seconds(*rc::gen::inRange<std::int64_t>(0, 86400));
  const Time t2 = t1 + milliseconds(*rc::gen::inRange<std::int64_t>(0, 3'600'000));
  const double a1 = oracle.time_dependent_expected_seconds(a, b, t1);
  const double a2 = oracle.time_dependent_expected_seconds(a, b, t2);
  RC_ASSERT((a1 == kInfinity) == (a2 == kInfinity));
  if (a1 < kInfinity) RC_ASSERT(to_seconds(t1 - kMorning) + a1 <= to_seconds(t2 - kMorning) + a2 + 1e-6);
}

// The one-to-all search is the same search run to the end: every node's arrival equals the route's.
RC_GTEST_PROP(TimeDependentProperties, ArrivalsAtEveryNodeEqualTheRoutes, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const map::TopoMap m = testing::building_map({.rows = 4, .columns = 5, .seed = seed, .door_fraction = 0.4});
  auto models = std::make_shared<FunctionEdgeModels>(testing::daily_models(m, 60.0));
  TravelPlanner oracle(m, models, {.slot_width = minutes(10)});
  const NodeIndex a = *rc::gen::inRange<std::size_t>(0, m.node_count());
  const Time t = kMorning + seconds(*rc::gen::inRange<std::int64_t>(0, 86400));
  const std::vector<double> all = oracle.time_dependent_arrivals(a, t);
  RC_ASSERT(all.size() == m.node_count());
  for (NodeIndex b = 0; b < m.node_count(); ++b) RC_ASSERT(all[b] == oracle.time_dependent_expected_seconds(a, b, t));
}

}  // namespace
}  // namespace rondo::plan
