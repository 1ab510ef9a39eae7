// The travel-time distribution with attempt-duration laws (RouteLeg::success_law, failure_law): a
// hand-worked route, the fixed-duration case as a special one, and the bracket against an
// independent reference (a memoised backward recursion over the budget left) on small routes.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "rondo/plan/travel_time_distribution.h"

namespace rondo::plan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// P(T <= budget) for legs whose durations are whole tenths of a second, failed attempts lasting at
// least a tenth: P(k, used) = Σ_s p w_s P(k + 1, used + s) + Σ_f (1 − p) w_f P(k, used + f).
double recursive_probability(const std::vector<RouteLeg>& legs, double budget) {
  const auto tenths = [](double seconds) { return static_cast<long>(std::lround(seconds * 10.0)); };
  const long limit = static_cast<long>(std::floor(budget * 10.0 + 1e-6));
  std::map<std::pair<std::size_t, long>, double> memo;
  std::function<double(std::size_t, long)> at = [&](std::size_t k, long used) -> double {
    if (used > limit) return 0.0;
    if (k == legs.size()) return 1.0;
    if (auto it = memo.find({k, used}); it != memo.end()) return it->second;
    const RouteLeg& leg = legs[k];
    const double p = std::min(leg.success_probability, 1.0);
    const auto law = [&](const std::vector<DurationPoint>& l) {
      std::vector<DurationPoint> out = l.empty() ? std::vector<DurationPoint>{{leg.attempt_seconds, 1.0}} : l;
      double total = 0.0;
      for (const DurationPoint& d : out) total += d.weight;
      for (DurationPoint& d : out) d.weight /= total;
      return out;
    };
    double v = 0.0;
    for (const DurationPoint& s : law(leg.success_law)) v += p * s.weight * at(k + 1, used + tenths(s.seconds));
    if (p < 1.0)
      for (const DurationPoint& f : law(leg.failure_law)) v += (1.0 - p) * f.weight * at(k, used + tenths(f.seconds));
    memo[{k, used}] = v;
    return v;
  };
  return at(0, 0);
}

TEST(AttemptLawDistribution, HandWorkedLeg) {
  // One leg, p = 1/2: success 10 s; failure 2 s or 6 s, even. T = 10 + the failures before it.
  // E = 10 + 4 × (1/2)/(1/2) = 14 s; 16 × 14 s over 224 cells: 1 s cells, so the bracket closes.
  const std::vector<RouteLeg> legs = {
      {.success_probability = 0.5, .attempt_seconds = 7.0, .success_law = {{10.0, 1.0}},
       .failure_law = {{2.0, 1.0}, {6.0, 1.0}}}};
  const auto d = TravelTimeDistribution::of_route(legs, {.cells = 224, .horizon_factor = 16.0});
  EXPECT_DOUBLE_EQ(d.expected_seconds(), 14.0);
  EXPECT_DOUBLE_EQ(d.cell_seconds(), 1.0);
  // T = 10: 1/2. T = 12: 1/4 × 1/2. T = 14: 1/8 × 1/4 (2 + 2). T = 16: 1/4 × 1/2 (one 6 s) and
  // 1/16 × 1/8 (2 + 2 + 2).
  const double within_12 = 0.5 + 0.125;
  const double within_16 = within_12 + 0.03125 + 0.125 + 0.0078125;
  EXPECT_NEAR(d.probability_within(9.9).upper, 0.0, 1e-15);
  EXPECT_NEAR(d.probability_within(10.0).lower, 0.5, 1e-12);
  EXPECT_NEAR(d.probability_within(12.0).lower, within_12, 1e-12);
  EXPECT_NEAR(d.probability_within(12.0).upper, within_12, 1e-12);
  EXPECT_NEAR(d.probability_within(16.0).lower, within_16, 1e-12);
  EXPECT_NEAR(d.probability_within(16.0).upper, within_16, 1e-12);
  EXPECT_DOUBLE_EQ(d.quantile(0.5).upper, 10.0);
  EXPECT_DOUBLE_EQ(d.quantile(0.6).upper, 12.0);
  EXPECT_DOUBLE_EQ(d.quantile(0.7).upper, 16.0);
}

TEST(AttemptLawDistribution, InstantFailuresCostNothing) {
  const std::vector<RouteLeg> legs = {
      {.success_probability = 0.2, .attempt_seconds = 5.0, .success_law = {{8.0, 1.0}}, .failure_law = {{0.0, 1.0}}}};
  const auto d = TravelTimeDistribution::of_route(legs, {.cells = 128, .horizon_factor = 16.0});
  EXPECT_DOUBLE_EQ(d.expected_seconds(), 8.0);
  EXPECT_NEAR(d.probability_within(7.9).upper, 0.0, 1e-12);
  EXPECT_NEAR(d.probability_within(8.0).lower, 1.0, 1e-12);
}

TEST(AttemptLawDistribution, BadPointsMakeTheRouteUnreachableAndZeroWeightsAreDropped) {
  const std::vector<RouteLeg> negative = {{.success_probability = 0.5, .attempt_seconds = 5.0,
                                           .success_law = {{-1.0, 1.0}}}};
  EXPECT_FALSE(TravelTimeDistribution::of_route(negative).reachable());
  const std::vector<RouteLeg> infinite = {{.success_probability = 0.5, .attempt_seconds = 5.0,
                                           .failure_law = {{kInf, 1.0}}}};
  EXPECT_FALSE(TravelTimeDistribution::of_route(infinite).reachable());
  const std::vector<RouteLeg> dropped = {{.success_probability = 0.5, .attempt_seconds = 5.0,
                                          .success_law = {{3.0, 1.0}, {100.0, 0.0}}}};
  EXPECT_DOUBLE_EQ(TravelTimeDistribution::of_route(dropped).expected_seconds(), 3.0 + 5.0);
}

RC_GTEST_PROP(AttemptLawProperties, SinglePointLawsAreTheFixedDuration, ()) {
  const auto count = *rc::gen::inRange<std::size_t>(1, 5);
  std::vector<RouteLeg> fixed;
  std::vector<RouteLeg> with_laws;
  for (std::size_t k = 0; k < count; ++k) {
    const double p = *rc::gen::inRange(20, 101) / 100.0;
    const double tau = *rc::gen::inRange(50, 4000) / 100.0;
    fixed.push_back({p, tau});
    with_laws.push_back({p, tau, {{tau, 1.0}}, {{tau, 2.0}}});
  }
  const DistributionOptions options{.cells = *rc::gen::element<std::size_t>(64, 1024)};
  const auto a = TravelTimeDistribution::of_route(fixed, options);
  const auto b = TravelTimeDistribution::of_route(with_laws, options);
  RC_ASSERT(std::abs(a.expected_seconds() - b.expected_seconds()) <= 1e-9 * a.expected_seconds());
  for (double q : {0.1, 0.5, 0.9, 0.99}) {
    RC_ASSERT(std::abs(a.quantile(q).upper - b.quantile(q).upper) <= 1e-9 * a.expected_seconds());
    RC_ASSERT(std::abs(a.quantile(q).lower - b.quantile(q).lower) <= 1e-9 * a.expected_seconds());
  }
}

std::vector<DurationPoint> random_law(double low_tenths, double high_tenths) {
  const auto points = *rc::gen::inRange<std::size_t>(1, 4);
  std::vector<DurationPoint> law;
  for (std::size_t i = 0; i < points; ++i) {
    law.push_back({*rc::gen::inRange(static_cast<int>(low_tenths), static_cast<int>(high_tenths)) / 10.0,
                   *rc::gen::inRange(1, 10) / 4.0});
  }
  return law;
}

RC_GTEST_PROP(AttemptLawProperties, BracketsTheRecursiveTruth, ()) {
  const auto count = *rc::gen::inRange<std::size_t>(1, 4);
  std::vector<RouteLeg> legs;
  for (std::size_t k = 0; k < count; ++k) {
    RouteLeg leg{.success_probability = *rc::gen::inRange(40, 101) / 100.0,
                 .attempt_seconds = *rc::gen::inRange(10, 300) / 10.0};
    if (*rc::gen::inRange(0, 4) != 0) leg.success_law = random_law(0, 300);
    if (*rc::gen::inRange(0, 4) != 0) leg.failure_law = random_law(1, 600);
    legs.push_back(std::move(leg));
  }
  const auto d = TravelTimeDistribution::of_route(legs, {.cells = *rc::gen::element<std::size_t>(64, 256, 1024)});
  RC_ASSERT(d.reachable());
  double previous_lower = 0.0;
  double previous_upper = 0.0;
  for (double factor : {0.3, 0.7, 1.0, 1.5, 2.5}) {
    const double budget = factor * d.expected_seconds();
    const ProbabilityBounds b = d.probability_within(budget);
    RC_ASSERT(0.0 <= b.lower);
    RC_ASSERT(b.lower <= b.upper);
    RC_ASSERT(b.upper <= 1.0 + 1e-12);
    RC_ASSERT(b.lower >= previous_lower - 1e-12);
    RC_ASSERT(b.upper >= previous_upper - 1e-12);
    previous_lower = b.lower;
    previous_upper = b.upper;
    const double truth = recursive_probability(legs, budget);
    RC_ASSERT(truth >= b.lower - 1e-9);
    RC_ASSERT(truth <= b.upper + 1e-9);
  }
  for (double q : {0.1, 0.5, 0.9}) {
    const QuantileBounds b = d.quantile(q);
    RC_ASSERT(b.lower <= b.upper);
    if (b.upper < kInf) RC_ASSERT(recursive_probability(legs, b.upper) >= q - 1e-9);
    if (b.lower > 0) RC_ASSERT(recursive_probability(legs, b.lower - 0.05) < q + 1e-9);
  }
}

// Computing only the first cells of the grid (DistributionOptions::computed_cells) changes nothing
// within them: every probability and every quantile found there is the whole grid's, to the bit,
// and a quantile beyond them says so (upper +inf) instead of guessing.
RC_GTEST_PROP(AttemptLawProperties, APartOfTheGridIsTheWholeGridsWithinIt, ()) {
  const auto count = *rc::gen::inRange<std::size_t>(1, 6);
  std::vector<RouteLeg> legs;
  for (std::size_t k = 0; k < count; ++k) {
    RouteLeg leg{.success_probability = *rc::gen::inRange(20, 101) / 100.0,
                 .attempt_seconds = *rc::gen::inRange(10, 300) / 10.0};
    if (*rc::gen::inRange(0, 3) != 0) leg.success_law = random_law(0, 900);
    if (*rc::gen::inRange(0, 3) != 0) leg.failure_law = random_law(1, 3000);
    legs.push_back(std::move(leg));
  }
  const auto cells = *rc::gen::element<std::size_t>(64, 256, 1024);
  const auto computed = *rc::gen::inRange<std::size_t>(1, cells + 1);
  const auto whole = TravelTimeDistribution::of_route(legs, {.cells = cells});
  const auto part = TravelTimeDistribution::of_route(legs, {.cells = cells, .computed_cells = computed});
  RC_ASSERT(whole.reachable() && part.reachable());
  RC_ASSERT(part.cell_seconds() == whole.cell_seconds());
  RC_ASSERT(part.horizon_seconds() <= whole.horizon_seconds());
  for (double f = 0.0; f <= 1.0; f += 0.05) {
    const double budget = f * part.horizon_seconds();
    RC_ASSERT(part.probability_within(budget).lower == whole.probability_within(budget).lower);
    RC_ASSERT(part.probability_within(budget).upper == whole.probability_within(budget).upper);
  }
  for (double q : {0.05, 0.5, 0.8, 0.9, 0.98}) {
    const QuantileBounds p = part.quantile(q);
    const QuantileBounds w = whole.quantile(q);
    if (p.upper < kInf) {
      RC_ASSERT(p.upper == w.upper);
      RC_ASSERT(p.lower == w.lower);
    } else {
      RC_ASSERT(w.upper >= part.horizon_seconds());
    }
  }
}

}  // namespace
}  // namespace rondo::plan
