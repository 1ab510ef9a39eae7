#include "rondo/learn/quantile_table.h"

#include <algorithm>
#include <cmath>

namespace rondo::learn {

QuantileTable QuantileTable::from_samples(std::vector<double> values, bool allow_negative) {
  QuantileTable out;
  if (values.empty()) return out;
  if (!allow_negative) {
    for (double& v : values) v = std::max(0.0, v);
  }
  std::sort(values.begin(), values.end());
  const double last = static_cast<double>(values.size() - 1);
  for (int k = 0; k < kKnots; ++k) {
    const double pos = level(k) * last;
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const auto hi = std::min(lo + 1, values.size() - 1);
    const double frac = pos - static_cast<double>(lo);
    out.values_[static_cast<std::size_t>(k)] = values[lo] + frac * (values[hi] - values[lo]);
  }
  // Interpolation of sorted values is already monotone; this guards against rounding.
  for (std::size_t k = 1; k < out.values_.size(); ++k) out.values_[k] = std::max(out.values_[k], out.values_[k - 1]);
  return out;
}

double QuantileTable::at(double q) const {
  if (!(q > level(0))) return values_.front();
  if (q >= level(kKnots - 1)) return values_.back();
  const double pos = q / 0.02 - 1.0;
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const auto hi = std::min(lo + 1, values_.size() - 1);
  const double frac = pos - static_cast<double>(lo);
  return values_[lo] + frac * (values_[hi] - values_[lo]);
}

Json QuantileTable::to_json() const {
  return Json(values_);
}

Result<QuantileTable> QuantileTable::from_json(const Json& j) {
  if (!j.is_array() || j.size() != static_cast<std::size_t>(kKnots)) {
    return Error::invalid("quantile table: expected an array of " + std::to_string(kKnots) + " numbers");
  }
  QuantileTable out;
  for (std::size_t k = 0; k < j.size(); ++k) {
    if (!j[k].is_number() || !std::isfinite(j[k].get<double>())) {
      return Error::invalid("quantile table: element " + std::to_string(k) + " is not a finite number");
    }
    out.values_[k] = j[k].get<double>();
    if (k > 0 && out.values_[k] < out.values_[k - 1]) {
      return Error::invalid("quantile table: values must be non-decreasing (element " + std::to_string(k) + ")");
    }
  }
  return out;
}

}  // namespace rondo::learn
