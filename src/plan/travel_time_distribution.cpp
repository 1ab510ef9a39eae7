#include "rondo/plan/travel_time_distribution.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rondo::plan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Grid positions are computed in floating point: τ/h or budget/h within this many cells of a whole
// number counts as that whole number, so exact multiples stay exact. The bracket therefore holds
// up to 1e-9 of a cell per rounding (docs/planning.md).
constexpr double kSlack = 1e-9;

enum class Rounding { kDown, kUp };

// The cumulative distribution over grid points 0..cells of Σ N_k m_k, m_k = τ_k/h rounded.
std::vector<double> rounded_cdf(std::span<const RouteLeg> legs, double cell, std::size_t cells, Rounding rounding) {
  std::vector<double> pmf(cells + 1, 0.0);
  std::vector<double> next(cells + 1, 0.0);
  pmf[0] = 1.0;
  for (const RouteLeg& leg : legs) {
    const double exact = leg.attempt_seconds / cell;
    const double rounded = rounding == Rounding::kDown ? std::floor(exact + kSlack) : std::ceil(exact - kSlack);
    if (rounded <= 0) continue;                  // N × 0 = 0: the distribution does not move
    if (rounded > static_cast<double>(cells)) {  // one attempt already leaves the grid
      std::fill(pmf.begin(), pmf.end(), 0.0);
      break;
    }
    const auto m = static_cast<std::size_t>(rounded);
    const double p = leg.success_probability;
    // g = f * law(N m): g[x] = p f[x − m] + (1 − p) g[x − m], the geometric's memorylessness.
    std::fill(next.begin(), next.begin() + static_cast<std::ptrdiff_t>(m), 0.0);
    for (std::size_t x = m; x <= cells; ++x) next[x] = p * pmf[x - m] + (1.0 - p) * next[x - m];
    pmf.swap(next);
  }
  double sum = 0.0;
  for (double& v : pmf) {
    sum += v;
    v = std::min(sum, 1.0);
  }
  return pmf;
}

}  // namespace

TravelTimeDistribution TravelTimeDistribution::unreachable() {
  TravelTimeDistribution d;
  d.reachable_ = false;
  d.expected_ = kInf;
  return d;
}

TravelTimeDistribution TravelTimeDistribution::of_route(std::span<const RouteLeg> legs,
                                                        const DistributionOptions& options) {
  double expected = 0.0;
  for (const RouteLeg& leg : legs) {
    if (!(leg.success_probability > 0.0) || !std::isfinite(leg.attempt_seconds) || leg.attempt_seconds < 0) {
      return unreachable();
    }
    expected += leg.attempt_seconds / std::min(leg.success_probability, 1.0);
  }
  if (!std::isfinite(expected)) return unreachable();
  TravelTimeDistribution d;
  d.expected_ = expected;
  if (expected <= 0.0) {  // no legs, or only instantaneous ones: T = 0
    d.cells_ = 0;
    d.cell_ = 0.0;
    d.fast_cdf_ = {1.0};
    d.slow_cdf_ = {1.0};
    return d;
  }
  std::vector<RouteLeg> clamped(legs.begin(), legs.end());
  for (RouteLeg& leg : clamped) leg.success_probability = std::min(leg.success_probability, 1.0);
  d.cells_ = std::max<std::size_t>(options.cells, 16);
  d.cell_ = std::max(options.horizon_factor, 2.0) * expected / static_cast<double>(d.cells_);
  d.fast_cdf_ = rounded_cdf(clamped, d.cell_, d.cells_, Rounding::kDown);
  d.slow_cdf_ = rounded_cdf(clamped, d.cell_, d.cells_, Rounding::kUp);
  return d;
}

ProbabilityBounds TravelTimeDistribution::probability_within(double budget_seconds) const {
  if (!reachable_ || std::isnan(budget_seconds) || budget_seconds < 0) return {0.0, 0.0};
  if (cells_ == 0) return {1.0, 1.0};
  // One grid point for both bounds: the last one at or below the budget (with kSlack).
  const double position = std::floor(budget_seconds / cell_ + kSlack);
  ProbabilityBounds b;
  if (position > static_cast<double>(cells_)) {  // beyond the grid: only the lower bound is known
    return {slow_cdf_.back(), 1.0};
  }
  const auto at = static_cast<std::size_t>(position);
  b.lower = slow_cdf_[at];  // P(T+ <= budget) <= P(T <= budget)
  b.upper = fast_cdf_[at];  // P(T- <= budget) >= P(T <= budget)
  b.upper = std::max(b.upper, b.lower);
  return b;
}

QuantileBounds TravelTimeDistribution::quantile(double q) const {
  if (!reachable_) return {kInf, kInf};
  if (cells_ == 0) return {0.0, 0.0};
  q = std::clamp(std::isnan(q) ? 1.0 : q, std::numeric_limits<double>::min(), 1.0);
  // Small slack on q so that a CDF that reaches q only up to rounding still counts.
  const double target = q - 1e-12;
  auto first_at_least = [&](const std::vector<double>& cdf) {
    return static_cast<std::size_t>(std::lower_bound(cdf.begin(), cdf.end(), target) - cdf.begin());
  };
  const std::size_t fast = first_at_least(fast_cdf_);
  const std::size_t slow = first_at_least(slow_cdf_);
  QuantileBounds b;
  b.lower = fast > cells_ ? horizon_seconds() : static_cast<double>(fast) * cell_;
  b.upper = slow > cells_ ? kInf : static_cast<double>(slow) * cell_;
  return b;
}

double TravelTimeDistribution::tail_mass() const {
  if (!reachable_) return 1.0;
  return std::max(0.0, 1.0 - slow_cdf_.back());
}

}  // namespace rondo::plan
