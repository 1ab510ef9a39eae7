// The travel-time distribution of a route: its bracket [lower, upper] must contain the truth,
// checked against two slow references (exact enumeration of attempt counts, and Monte Carlo with
// a seeded generator); it closes when attempt times are whole grid cells; probabilities stay in
// [0, 1] and grow with the budget.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "rondo/plan/exact_solver.h"
#include "rondo/plan/travel_time_distribution.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

// P(Σ N_k τ_k <= budget) by enumerating attempt counts depth first: exact up to rounding, slow.
double enumerated_probability(const std::vector<RouteLeg>& legs, double budget, std::size_t k = 0, double used = 0) {
  if (k == legs.size()) return used <= budget + 1e-9 ? 1.0 : 0.0;
  const double p = legs[k].success_probability;
  double total = 0.0;
  double mass = p;  // P(N = n) = p (1 − p)^(n − 1)
  for (std::size_t n = 1; used + static_cast<double>(n) * legs[k].attempt_seconds <= budget + 1e-9 && mass > 1e-300;
       ++n) {
    total +=
        mass * enumerated_probability(legs, budget, k + 1, used + static_cast<double>(n) * legs[k].attempt_seconds);
    mass *= 1.0 - p;
  }
  return total;
}

TEST(TravelTimeDistribution, EmptyRouteIsZeroAndUnreachableIsNever) {
  const auto here = TravelTimeDistribution::of_route({});
  EXPECT_TRUE(here.reachable());
  EXPECT_EQ(here.expected_seconds(), 0.0);
  EXPECT_EQ(here.probability_within(0.0).lower, 1.0);
  EXPECT_EQ(here.quantile(0.9).upper, 0.0);
  const auto never = TravelTimeDistribution::unreachable();
  EXPECT_FALSE(never.reachable());
  EXPECT_EQ(never.expected_seconds(), kInfinity);
  EXPECT_EQ(never.probability_within(1e9).upper, 0.0);
  EXPECT_EQ(never.quantile(0.5).lower, kInfinity);
  const std::vector<RouteLeg> closed = {{1.0, 5.0}, {0.0, 5.0}};
  EXPECT_FALSE(TravelTimeDistribution::of_route(closed).reachable());
}

TEST(TravelTimeDistribution, CertainLegsGiveAStep) {
  const std::vector<RouteLeg> legs = {{1.0, 10.0}, {1.0, 20.0}};
  const auto d = TravelTimeDistribution::of_route(legs);
  EXPECT_DOUBLE_EQ(d.expected_seconds(), 30.0);
  EXPECT_EQ(d.probability_within(29.0).upper, 0.0);
  EXPECT_EQ(d.probability_within(31.0).lower, 1.0);
  const QuantileBounds q = d.quantile(0.5);
  EXPECT_LE(q.lower, 30.0);
  EXPECT_GE(q.upper, 30.0);
  EXPECT_LE(q.upper - q.lower, 2 * d.cell_seconds() + 1e-9);
}

TEST(TravelTimeDistribution, WholeCellAttemptsAreExact) {
  // horizon 16 × 40 s over 640 cells: 1 s cells, and every τ is a whole number of seconds.
  const std::vector<RouteLeg> legs = {{0.5, 10.0}, {0.8, 8.0}, {1.0, 2.0}};  // E = 20 + 10 + 2 = 32
  const auto d = TravelTimeDistribution::of_route(legs, {.cells = 512, .horizon_factor = 16.0});
  EXPECT_DOUBLE_EQ(d.cell_seconds(), 1.0);
  for (double budget : {19.0, 20.0, 28.0, 30.0, 37.5, 50.0, 100.0}) {
    const ProbabilityBounds b = d.probability_within(budget);
    const double truth = enumerated_probability(legs, budget);
    EXPECT_NEAR(b.lower, truth, 1e-12) << budget;
    EXPECT_NEAR(b.upper, truth, 1e-12) << budget;
  }
}

TEST(TravelTimeDistribution, BracketContainsMonteCarlo) {
  std::mt19937_64 rng(42);
  const std::vector<RouteLeg> legs = {{0.35, 7.3}, {0.9, 13.1}, {0.6, 2.7}, {0.99, 31.4}};
  const auto d = TravelTimeDistribution::of_route(legs);
  constexpr int kSamples = 20000;
  std::vector<double> samples;
  for (int s = 0; s < kSamples; ++s) {
    double t = 0;
    for (const RouteLeg& leg : legs) {
      std::geometric_distribution<int> failures(leg.success_probability);
      t += (failures(rng) + 1) * leg.attempt_seconds;
    }
    samples.push_back(t);
  }
  for (double budget : {40.0, 60.0, 80.0, 120.0, 200.0}) {
    double within = 0;
    for (double t : samples) within += t <= budget ? 1 : 0;
    const double p = within / kSamples;
    const double sigma = std::sqrt(std::max(p * (1 - p), 1e-4) / kSamples);
    const ProbabilityBounds b = d.probability_within(budget);
    EXPECT_GE(p, b.lower - 5 * sigma) << budget;
    EXPECT_LE(p, b.upper + 5 * sigma) << budget;
    EXPECT_LE(b.upper - b.lower, 0.05) << budget;
  }
}

RC_GTEST_PROP(DistributionProperties, BracketsTheEnumeratedTruth, ()) {
  const auto count = *rc::gen::inRange<std::size_t>(1, 4);
  std::vector<RouteLeg> legs;
  for (std::size_t k = 0; k < count; ++k) {
    legs.push_back({.success_probability = *rc::gen::inRange(30, 101) / 100.0,
                    .attempt_seconds = *rc::gen::inRange(100, 3000) / 100.0});
  }
  const auto d = TravelTimeDistribution::of_route(legs, {.cells = *rc::gen::element<std::size_t>(64, 512, 2048)});
  double previous_lower = 0.0;
  double previous_upper = 0.0;
  for (double factor : {0.5, 0.9, 1.0, 1.3, 2.0, 3.0}) {
    const double budget = factor * d.expected_seconds();
    const ProbabilityBounds b = d.probability_within(budget);
    RC_ASSERT(0.0 <= b.lower);
    RC_ASSERT(b.lower <= b.upper);
    RC_ASSERT(b.upper <= 1.0);
    RC_ASSERT(b.lower >= previous_lower);
    RC_ASSERT(b.upper >= previous_upper);
    previous_lower = b.lower;
    previous_upper = b.upper;
    const double truth = enumerated_probability(legs, budget);
    RC_ASSERT(truth >= b.lower - 1e-9);
    RC_ASSERT(truth <= b.upper + 1e-9);
  }
  for (double q : {0.1, 0.5, 0.9}) {
    const QuantileBounds b = d.quantile(q);
    RC_ASSERT(b.lower <= b.upper);
    // The truth at the bounds: P(T <= upper) >= q, and P(T <= just below lower) < q.
    if (b.upper < kInfinity) RC_ASSERT(enumerated_probability(legs, b.upper) >= q - 1e-9);
    if (b.lower > 0) RC_ASSERT(enumerated_probability(legs, b.lower - 1e-6) < q + 1e-9);
  }
}

TEST(TravelTimeDistribution, FromAPolicy) {
  const map::TopoMap m = testing::small_map({"A", "B", "C"}, {"A>B", "B>C"});
  const Mdp mdp = testing::outcomes_mdp(m, {{0.5, 4.0}, {1.0, 2.0}});
  const Policy policy = ExactSolver{}.solve(mdp, 2).value().policy;
  const auto d = policy.travel_time_distribution(0);
  EXPECT_DOUBLE_EQ(d.expected_seconds(), policy.expected_seconds(0));
  EXPECT_NEAR(d.probability_within(7.0).estimate(), 0.5, 1e-9);    // one attempt on A>B (T = 6)
  EXPECT_NEAR(d.probability_within(11.0).estimate(), 0.75, 1e-9);  // at most two (T = 10)
  EXPECT_FALSE(ExactSolver{}.solve(mdp, 0).value().policy.travel_time_distribution(2).reachable());
}

}  // namespace
}  // namespace rondo::plan
