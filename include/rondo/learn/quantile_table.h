// A compact, monotone description of a distribution of durations: its quantiles at fixed levels,
// linearly interpolated between them. What the duration models store and serialise.
//
//   QuantileTable q = QuantileTable::from_samples({12.0, 9.5, 30.1, 11.0});
//   double p90 = q.at(0.9);          // non-decreasing in the level, >= 0
#pragma once

#include <span>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"

namespace rondo::learn {

class QuantileTable {
 public:
  // Levels 0.02, 0.04, ..., 0.98 (49 knots): fine enough for pinball losses, small in JSON.
  static constexpr int kKnots = 49;
  static double level(int knot) { return 0.02 * (knot + 1); }

  QuantileTable() : values_(kKnots, 0.0) {}
  // Empirical quantiles (linear interpolation between order statistics) of `values`; all zero
  // when `values` is empty. Negative values are clamped to 0 unless `allow_negative` (residuals).
  static QuantileTable from_samples(std::vector<double> values, bool allow_negative = false);

  // The q-quantile, q clamped to [0.02, 0.98] (the table does not extrapolate the tails).
  // Non-decreasing in q.
  double at(double q) const;
  const std::vector<double>& values() const { return values_; }

  Json to_json() const;
  static Result<QuantileTable> from_json(const Json& j);

 private:
  std::vector<double> values_;  // non-decreasing, size kKnots
};

}  // namespace rondo::learn
