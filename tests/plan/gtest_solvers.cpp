// The exact solver and value iteration: hand-made cases (retries, p = 0 edges, dead ends,
// unreachable targets, a risky shortcut against a safe detour), and properties on random maps of
// 10-2,000 nodes: the two agree, the exact policy satisfies the Bellman equation and is optimal
// among one-step deviations, and following next_edge() reaches the target.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>

#include "random_map.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/value_iteration.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

using testing::outcomes_mdp;
using testing::small_map;

Solution exact(const Mdp& mdp, NodeIndex target) {
  return ExactSolver{}.solve(mdp, target).value();
}
Solution iterate(const Mdp& mdp, NodeIndex target, double tolerance = 1e-9, bool gauss_seidel = false) {
  return ValueIteration({.tolerance = tolerance, .gauss_seidel = gauss_seidel}).solve(mdp, target).value();
}

// Relative difference, with both infinite counting as equal.
double relative_gap(double a, double b) {
  if (a == kInfinity || b == kInfinity) return a == b ? 0.0 : kInfinity;
  return std::abs(a - b) / std::max(1.0, std::abs(b));
}

TEST(Solvers, RetriesMakeARiskyShortcutWorseThanASafeDetour) {
  // A>C costs 10 per attempt at p = 0.2 (50 expected); A>B>C is 15 + 15 always succeeding.
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>C", "A>B", "B>C"});
  const Mdp mdp = outcomes_mdp(m, {{0.2, 10.0}, {1.0, 15.0}, {1.0, 15.0}});
  for (const Solution& s : {exact(mdp, 2), iterate(mdp, 2)}) {
    EXPECT_EQ(s.policy.next_edge(0), 1u);
    EXPECT_NEAR(s.policy.expected_seconds(0), 30.0, 1e-6);
    EXPECT_NEAR(s.policy.expected_seconds(1), 15.0, 1e-6);
    EXPECT_EQ(s.policy.expected_seconds(2), 0.0);
    EXPECT_FALSE(s.policy.next_edge(2).has_value());
  }
}

TEST(Solvers, AClosedEdgeIsNeverTakenAndItsNodeIsUnreachable) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B"});
  const Mdp mdp = outcomes_mdp(m, {{0.0, 10.0}});
  for (const Solution& s : {exact(mdp, 1), iterate(mdp, 1)}) {
    EXPECT_EQ(s.policy.expected_seconds(0), kInfinity);
    EXPECT_FALSE(s.policy.next_edge(0).has_value());
    EXPECT_FALSE(s.policy.reaches_target(0));
    EXPECT_TRUE(s.policy.route(0).empty());
  }
}

TEST(Solvers, DeadEndsAndDisconnectedNodesGetInfinityNotNaN) {
  // D is a dead end (no out-edges); E is not connected at all; C only reaches D.
  const map::TopoMap m = small_map({"A", "B", "C", "D", "E"}, {"A>B", "C>D", "B>A"});
  const Mdp mdp = outcomes_mdp(m, {{0.5, 2.0}, {1.0, 1.0}, {1.0, 1.0}});
  for (const Solution& s : {exact(mdp, 1), iterate(mdp, 1)}) {
    EXPECT_NEAR(s.policy.expected_seconds(0), 4.0, 1e-6);
    for (NodeIndex i : {2u, 3u, 4u}) {
      EXPECT_EQ(s.policy.expected_seconds(i), kInfinity) << i;
      EXPECT_FALSE(s.policy.next_edge(i).has_value()) << i;
    }
  }
  EXPECT_EQ(iterate(mdp, 1).status, SolveStatus::kConverged);
  // A dead-end target: only itself reaches it.
  const Solution to_e = exact(mdp, 4);
  EXPECT_EQ(to_e.policy.expected_seconds(4), 0.0);
  EXPECT_EQ(to_e.policy.expected_seconds(0), kInfinity);
  EXPECT_EQ(iterate(mdp, 4).status, SolveStatus::kConverged);
}

TEST(Solvers, TargetOutsideTheMapIsAnError) {
  const map::TopoMap m = small_map({"A"}, {});
  const Mdp mdp = outcomes_mdp(m, {});
  EXPECT_FALSE(ExactSolver{}.solve(mdp, 1).ok());
  EXPECT_FALSE(ValueIteration{}.solve(mdp, 5).ok());
  EXPECT_EQ(exact(mdp, 0).policy.expected_seconds(0), 0.0);
}

TEST(Solvers, ValueIterationStopsAtItsSweepLimit) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B"});
  const Mdp mdp = outcomes_mdp(m, {{0.01, 1.0}});  // converges slowly: 1 − p = 0.99 per sweep
  const Solution s = ValueIteration({.tolerance = 1e-12, .max_sweeps = 5}).solve(mdp, 1).value();
  EXPECT_EQ(s.status, SolveStatus::kSweepLimit);
  EXPECT_EQ(s.sweeps, 5u);
  EXPECT_LT(s.policy.expected_seconds(0), 100.0);  // from below
  const Solution done = iterate(mdp, 1, 1e-10);
  EXPECT_EQ(done.status, SolveStatus::kConverged);
  EXPECT_NEAR(done.policy.expected_seconds(0), 100.0, 1e-6);
}

// Checks a policy against its MDP: Bellman equation on the chosen edge, no better one-step
// deviation, finite values exactly where the target is reachable, and routes that end there.
void expect_consistent(const Mdp& mdp, const Policy& policy, double tolerance) {
  const map::TopoMap& m = mdp.topology();
  for (NodeIndex i = 0; i < mdp.node_count(); ++i) {
    const double v = policy.expected_seconds(i);
    ASSERT_FALSE(std::isnan(v));
    if (i == policy.target()) {
      ASSERT_EQ(v, 0.0);
      continue;
    }
    // The best one-step value from i.
    double best = kInfinity;
    for (EdgeIndex e : m.out_edges(i))
      best = std::min(best, mdp.expected_crossing_seconds(e) + policy.expected_seconds(m.to_index(e)));
    if (v == kInfinity) {
      ASSERT_EQ(best, kInfinity) << "node " << i << " could reach the target";
      ASSERT_FALSE(policy.next_edge(i).has_value());
      continue;
    }
    const auto e = policy.next_edge(i);
    ASSERT_TRUE(e.has_value()) << "node " << i;
    const double chosen = mdp.expected_crossing_seconds(*e) + policy.expected_seconds(m.to_index(*e));
    ASSERT_NEAR(v, chosen, tolerance * std::max(1.0, v)) << "Bellman at node " << i;
    ASSERT_LE(chosen, best + tolerance * std::max(1.0, v)) << "a better edge at node " << i;
    const auto route = policy.route(i);
    ASSERT_FALSE(route.empty());
    ASSERT_EQ(route.front().from, i);
    ASSERT_EQ(route.back().to, policy.target());
  }
}

struct Case {
  std::size_t nodes;
  std::uint64_t seed;
  double min_probability;
  bool gauss_seidel = false;
};

void check_agreement(const Case& c) {
  const map::TopoMap m = testing::random_map({.nodes = c.nodes, .seed = c.seed});
  const Mdp mdp =
      testing::outcomes_mdp(m, testing::random_outcomes(m, {.seed = c.seed, .min_probability = c.min_probability}));
  const NodeIndex target = static_cast<NodeIndex>(c.seed % c.nodes);
  const Solution ex = exact(mdp, target);
  expect_consistent(mdp, ex.policy, 1e-12);
  // The default solver used its bucket ring here (τ/p spans 1..300 s); the heap agrees with it.
  ASSERT_TRUE(ExactSolver{}.uses_buckets(mdp));
  const Solution heap = ExactSolver({.max_buckets = 0}).solve(mdp, target).value();
  for (NodeIndex i = 0; i < m.node_count(); ++i) {
    ASSERT_LE(relative_gap(heap.policy.expected_seconds(i), ex.policy.expected_seconds(i)), 1e-12) << "node " << i;
  }
  // Relative-change tolerance 1e-9; agreement asserted at 1e-6 relative (docs/planning.md: with
  // p >= 0.2 the remaining error is at most (1 − p)/p = 4 times the last change, and in practice
  // far less).
  const Solution vi = iterate(mdp, target, 1e-9, c.gauss_seidel);
  ASSERT_EQ(vi.status, SolveStatus::kConverged);
  for (NodeIndex i = 0; i < m.node_count(); ++i) {
    ASSERT_LE(relative_gap(vi.policy.expected_seconds(i), ex.policy.expected_seconds(i)), 1e-6) << "node " << i;
    ASSERT_LE(vi.policy.expected_seconds(i), ex.policy.expected_seconds(i) * (1 + 1e-12)) << "VI from below";
  }
  expect_consistent(mdp, vi.policy, 1e-6);
}

TEST(Solvers, AgreeOnLargeRandomMaps) {
  // The 2,000-node end of the range, a few instances only (the suite also runs under ASan).
  for (const Case& c : {Case{2000, 1, 0.2}, Case{2000, 2, 0.5, true}, Case{1000, 3, 0.2, true}}) check_agreement(c);
}

RC_GTEST_PROP(SolverProperties, ValueIterationAgreesWithTheExactSolver, ()) {
  const Case c{*rc::gen::inRange<std::size_t>(10, 200), *rc::gen::arbitrary<std::uint32_t>(),
               *rc::gen::element(0.2, 0.5, 0.9), *rc::gen::arbitrary<bool>()};
  check_agreement(c);
}

// Dial's ring of buckets against the binary heap, with crossing costs spread over five orders of
// magnitude and rings from none to wide: the ring is used exactly when it fits, and both give
// policies that satisfy the Bellman equation with the same expected times.
RC_GTEST_PROP(SolverProperties, TheBucketRingAndTheHeapAgree, ()) {
  const auto nodes = *rc::gen::inRange<std::size_t>(2, 300);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const map::TopoMap m = testing::random_map({.nodes = nodes, .seed = seed});
  const double max_seconds = *rc::gen::element(2.0, 100.0, 1e4);
  const Mdp mdp = outcomes_mdp(
      m, testing::random_outcomes(m, {.seed = seed, .min_probability = 0.1, .min_seconds = 0.1,
                                      .max_seconds = max_seconds}));
  const std::size_t ring = *rc::gen::element<std::size_t>(0, 2, 16, 1024, std::size_t{1} << 16);
  const ExactSolver solver({.max_buckets = ring, .use_dead_ends = *rc::gen::arbitrary<bool>()});
  const bool fits = mdp.min_crossing_seconds() < kInfinity && ring >= 2 &&
                    mdp.max_crossing_seconds() / mdp.min_crossing_seconds() <= static_cast<double>(ring - 2);
  RC_ASSERT(solver.uses_buckets(mdp) == fits);
  const NodeIndex target = *rc::gen::inRange<std::size_t>(0, nodes);
  const Solution a = solver.solve(mdp, target).value();
  const Solution b = ExactSolver({.max_buckets = 0, .use_dead_ends = false}).solve(mdp, target).value();
  for (NodeIndex i = 0; i < nodes; ++i) {
    RC_ASSERT(relative_gap(a.policy.expected_seconds(i), b.policy.expected_seconds(i)) <= 1e-12);
  }
  expect_consistent(mdp, a.policy, 1e-12);
}

// The default solver searches the core and fills the dead ends from their exits (dead_ends.h);
// it must give the plain reverse Dijkstra's expected times for targets anywhere: in the core, on a
// door, inside a region. Sparse random maps have many dead ends; closed edges cut some off.
RC_GTEST_PROP(SolverProperties, SkippingTheDeadEndsChangesNoExpectedTime, ()) {
  const auto nodes = *rc::gen::inRange<std::size_t>(2, 300);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const bool building = *rc::gen::arbitrary<bool>();
  const map::TopoMap m = building
                             ? testing::corridor_building_map({.floors = 2, .corridor_nodes = 6, .rooms_per_side = 2})
                             : testing::random_map({.nodes = nodes, .seed = seed, .max_out_degree = 2});
  const Mdp mdp = outcomes_mdp(m, testing::random_outcomes(m, {.seed = seed, .closed_fraction = 0.1}));
  const DeadEnds& d = mdp.dead_ends();
  // Targets of every kind, when the map has them.
  std::vector<NodeIndex> targets{static_cast<NodeIndex>(seed % m.node_count())};
  if (d.region_count() > 0) {
    const auto r = static_cast<std::uint32_t>(seed % d.region_count());
    targets.push_back(d.door(r));
    targets.push_back(d.nodes(r).back());
  }
  const ExactSolver plain({.use_dead_ends = false});
  for (NodeIndex target : targets) {
    const Solution a = ExactSolver{}.solve(mdp, target).value();
    const Solution b = plain.solve(mdp, target).value();
    for (NodeIndex i = 0; i < m.node_count(); ++i) {
      RC_ASSERT(relative_gap(a.policy.expected_seconds(i), b.policy.expected_seconds(i)) <= 1e-12);
    }
    expect_consistent(mdp, a.policy, 1e-12);
  }
}

RC_GTEST_PROP(SolverProperties, ExpectedTimesAreFiniteExactlyWhereTheTargetIsReachable, ()) {
  const auto nodes = *rc::gen::inRange<std::size_t>(2, 60);
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const map::TopoMap m = testing::random_map({.nodes = nodes, .seed = seed, .max_out_degree = 2});
  const Mdp mdp = outcomes_mdp(m, testing::random_outcomes(m, {.seed = seed, .closed_fraction = 0.3}));
  const NodeIndex target = *rc::gen::inRange<std::size_t>(0, nodes);
  const Solution s = exact(mdp, target);
  // Reference reachability: repeated relaxation over usable edges.
  std::vector<bool> reach(nodes, false);
  reach[target] = true;
  for (bool changed = true; changed;) {
    changed = false;
    for (EdgeIndex e = 0; e < m.edge_count(); ++e) {
      if (mdp.usable(e) && reach[m.to_index(e)] && !reach[m.from_index(e)]) reach[m.from_index(e)] = changed = true;
    }
  }
  for (NodeIndex i = 0; i < nodes; ++i) RC_ASSERT(reach[i] == (s.policy.expected_seconds(i) < kInfinity));
}

}  // namespace
}  // namespace rondo::plan
