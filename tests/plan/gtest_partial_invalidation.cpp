// An online update of one edge leaves TravelPlanner's cached M_t and policies that the edge does not
// touch: a property on random buildings (every cached answer after any sequence of one-edge updates
// and snapshot swaps equals a fresh oracle's), a case that shows an untouched policy kept and a
// touched one solved again, and Policy::survives_edge_change against a fresh solve.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "patchable_models.h"
#include "random_map.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/travel_planner.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

using testing::PatchableEdgeModels;

const Time kMorning = Time{} + hours(24 * 16000 + 8);

bool same(double a, double b) {
  if (!std::isfinite(a) || !std::isfinite(b)) return a == b;
  return std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b));
}

RC_GTEST_PROP(PartialInvalidation, CachedAnswersEqualAFreshOracleAfterUpdates, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const map::TopoMap m = testing::building_map({.rows = 4, .columns = 5, .seed = seed, .door_fraction = 0.3});
  const FunctionEdgeModels daily = testing::daily_models(m);
  auto models = std::make_shared<PatchableEdgeModels>(
      m.edge_count(), [daily](map::EdgeIndex e, Time t) { return daily.outcome(e, t); });
  TravelPlanner cached(m, models, {.slot_width = minutes(15)});
  const int steps = *rc::gen::inRange(1, 40);
  for (int k = 0; k < steps; ++k) {
    const int what = *rc::gen::inRange(0, 10);
    if (what < 3) {
      // One edge: worse, better, closed, or the same again.
      const map::EdgeIndex e = *rc::gen::inRange<std::size_t>(0, m.edge_count());
      const double p = *rc::gen::element(1.0, 0.5, 0.0, 1.2);
      const double tau = *rc::gen::element(1.0, 0.25, 3.0);
      models->change(e, p, tau);
    } else if (what == 3) {
      models->change_all(*rc::gen::element(1.0, 0.8), *rc::gen::element(1.0, 1.5));
    } else {
      const NodeIndex a = *rc::gen::inRange<std::size_t>(0, m.node_count());
      const NodeIndex b = *rc::gen::inRange<std::size_t>(0, m.node_count());
      const Time t = kMorning + minutes(15 * *rc::gen::inRange(0, 4)) + seconds(*rc::gen::inRange(0, 900));
      TravelPlanner fresh(m, models, {.slot_width = minutes(15)});
      RC_ASSERT(same(cached.expected_seconds(a, b, t), fresh.expected_seconds(a, b, t)));
      if (what == 9) {
        RC_ASSERT(
            same(cached.time_dependent_expected_seconds(a, b, t), fresh.time_dependent_expected_seconds(a, b, t)));
      }
    }
  }
}

TEST(PartialInvalidation, AnUpdateKeepsThePoliciesItDoesNotTouch) {
  // A -> B -> C, and A <-> D off the way to C.
  const map::TopoMap m = testing::small_map({"A", "B", "C", "D"}, {"A>B", "B>C", "A>D", "D>A"});
  auto models = std::make_shared<PatchableEdgeModels>(m.edge_count(), [](map::EdgeIndex, Time) {
    return EdgeCrossing{1.0, 10.0};
  });
  TravelPlanner oracle(m, models);
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 2, kMorning), 20.0);  // policy to C
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 3, kMorning), 10.0);  // policy to D: takes A>D
  models->change(*m.find_edge("A_D"), 1.0, 3.0);                    // slower: the policy to C does not take it
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 2, kMorning), 20.0);
  EXPECT_EQ(oracle.policies_kept(), 1u);
  EXPECT_EQ(oracle.policies_resolved(), 0u);
  // The one to D does: solved again, with the new time.
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 3, kMorning), 30.0);
  EXPECT_EQ(oracle.policies_resolved(), 1u);
  // A faster A>D is no shortcut to C either.
  models->change(*m.find_edge("A_D"), 1.0, 0.5);
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 2, kMorning), 20.0);
  EXPECT_EQ(oracle.policies_resolved(), 1u);
  // A snapshot swap says nothing about which edges: everything is solved again.
  models->change_all(0.5, 1.0);
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 2, kMorning), 40.0);
  EXPECT_EQ(oracle.policies_resolved(), 2u);
}

RC_GTEST_PROP(SurvivesEdgeChange, AgreesWithAFreshSolve, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const map::TopoMap m = testing::random_map({.nodes = *rc::gen::inRange<std::size_t>(2, 25), .seed = seed});
  RC_PRE(m.edge_count() > 0);
  std::vector<EdgeCrossing> outcomes = testing::random_outcomes(m, {.seed = seed});
  const NodeIndex target = *rc::gen::inRange<std::size_t>(0, m.node_count());
  const Policy before = ExactSolver{}.solve(Mdp::from_outcomes(m, outcomes, kMorning).value(), target).value().policy;
  const map::EdgeIndex e = *rc::gen::inRange<std::size_t>(0, m.edge_count());
  outcomes[e].expected_seconds *= *rc::gen::element(0.1, 0.5, 1.0, 2.0, 10.0);
  const Mdp after_mdp = Mdp::from_outcomes(m, outcomes, kMorning).value();
  const Policy after = ExactSolver{}.solve(after_mdp, target).value().policy;
  if (before.survives_edge_change(e, m.from_index(e), m.to_index(e), after_mdp.expected_crossing_seconds(e))) {
    for (NodeIndex n = 0; n < m.node_count(); ++n)
      RC_ASSERT(same(before.expected_seconds(n), after.expected_seconds(n)));
  }
}

}  // namespace
}  // namespace rondo::plan
