#include "rondo/plan/travel_time_distribution.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace rondo::plan {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Grid positions are computed in floating point: τ/h or budget/h within this many cells of a whole
// number counts as that whole number, so exact multiples stay exact. The bracket therefore holds
// up to 1e-9 of a cell per rounding (docs/planning.md).
constexpr double kSlack = 1e-9;

enum class Rounding { kDown, kUp };

std::size_t rounded_cells(double seconds, double cell, Rounding rounding) {
  const double exact = seconds / cell;
  const double r = rounding == Rounding::kDown ? std::floor(exact + kSlack) : std::ceil(exact - kSlack);
  return r <= 0 ? 0 : (r > 1e18 ? std::numeric_limits<std::size_t>::max() : static_cast<std::size_t>(r));
}

// A law rounded to whole cells: (cells, weight) with points beyond the grid left out (their mass
// never arrives within it). An empty law is the single point `fallback`.
std::vector<std::pair<std::size_t, double>> rounded_law(const std::vector<DurationPoint>& law, double fallback,
                                                        double cell, std::size_t cells, Rounding rounding) {
  std::vector<std::pair<std::size_t, double>> out;
  if (law.empty()) {
    const std::size_t m = rounded_cells(fallback, cell, rounding);
    if (m <= cells) out.emplace_back(m, 1.0);
    return out;
  }
  for (const DurationPoint& point : law) {
    const std::size_t m = rounded_cells(point.seconds, cell, rounding);
    if (m <= cells) out.emplace_back(m, point.weight);
  }
  return out;
}

// next = pmf * X, X the leg's crossing time (laws already normalised by of_route):
// g[x] = p (f * S)[x] + (1 − p) Σ_j F_j g[x − j], the j = 0 term moved to the left side.
void add_leg_with_laws(const RouteLeg& leg, double cell, Rounding rounding, const std::vector<double>& pmf,
                       std::vector<double>& next) {
  const std::size_t cells = pmf.size() - 1;
  const auto success = rounded_law(leg.success_law, leg.attempt_seconds, cell, cells, rounding);
  const auto failure = rounded_law(leg.failure_law, leg.attempt_seconds, cell, cells, rounding);
  const double p = leg.success_probability;
  double at_zero = 0.0;
  for (const auto& [m, w] : failure)
    if (m == 0) at_zero += w;
  const double scale = 1.0 / (1.0 - (1.0 - p) * at_zero);  // p > 0, so at_zero (1 − p) < 1
  std::fill(next.begin(), next.end(), 0.0);
  for (const auto& [m, w] : success)
    for (std::size_t x = m; x <= cells; ++x) next[x] += p * w * pmf[x - m];
  for (std::size_t x = 0; x <= cells; ++x) {
    double v = next[x];
    for (const auto& [m, w] : failure)
      if (m > 0 && m <= x) v += (1.0 - p) * w * next[x - m];
    next[x] = v * scale;
  }
}

// The cumulative distribution over grid points 0..cells of Σ N_k m_k, m_k = τ_k/h rounded.
std::vector<double> rounded_cdf(std::span<const RouteLeg> legs, double cell, std::size_t cells, Rounding rounding) {
  std::vector<double> pmf(cells + 1, 0.0);
  std::vector<double> next(cells + 1, 0.0);
  pmf[0] = 1.0;
  for (const RouteLeg& leg : legs) {
    if (!leg.success_law.empty() || !leg.failure_law.empty()) {
      add_leg_with_laws(leg, cell, rounding, pmf, next);
      pmf.swap(next);
      continue;
    }
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

// Drops points without a positive finite weight and scales the rest to sum 1; false when a point
// has a negative or non-finite duration.
bool normalise(std::vector<DurationPoint>& law) {
  std::erase_if(law, [](const DurationPoint& d) { return !(d.weight > 0.0) || !std::isfinite(d.weight); });
  double total = 0.0;
  for (const DurationPoint& d : law) {
    if (!std::isfinite(d.seconds) || d.seconds < 0) return false;
    total += d.weight;
  }
  for (DurationPoint& d : law) d.weight /= total;
  return true;
}

double mean(const std::vector<DurationPoint>& law) {
  double m = 0.0;
  for (const DurationPoint& d : law) m += d.seconds * d.weight;
  return m;
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
  std::vector<RouteLeg> clamped(legs.begin(), legs.end());
  for (RouteLeg& leg : clamped) {
    if (!(leg.success_probability > 0.0) || !std::isfinite(leg.attempt_seconds) || leg.attempt_seconds < 0 ||
        !normalise(leg.success_law) || !normalise(leg.failure_law)) {
      return unreachable();
    }
    leg.success_probability = std::min(leg.success_probability, 1.0);
    const double p = leg.success_probability;
    if (leg.success_law.empty() && leg.failure_law.empty()) {
      expected += leg.attempt_seconds / p;
    } else {
      const double s = leg.success_law.empty() ? leg.attempt_seconds : mean(leg.success_law);
      const double f = leg.failure_law.empty() ? leg.attempt_seconds : mean(leg.failure_law);
      expected += s + (p < 1.0 ? f * (1.0 - p) / p : 0.0);
    }
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
  const std::size_t cells = std::max<std::size_t>(options.cells, 16);
  d.cell_ = std::max(options.horizon_factor, 2.0) * expected / static_cast<double>(cells);
  d.cells_ = options.computed_cells > 0 ? std::min(options.computed_cells, cells) : cells;
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
