#include "rondo/learn/static_model.h"

#include <algorithm>
#include <cmath>

namespace rondo::learn {

Json StaticBinaryModel::to_json() const {
  return Json{{"type", "static"}, {"mean", mean_}};
}

Json StaticDurationModel::to_json() const {
  return Json{{"type", "static"}, {"mean", mean_}, {"quantiles", quantiles_.to_json()}};
}

std::shared_ptr<const StaticBinaryModel> fit_static_binary(std::span<const BinarySample> samples) {
  if (samples.empty()) return std::make_shared<const StaticBinaryModel>(0.5);
  double successes = 0;
  for (const auto& s : samples) successes += s.value ? 1.0 : 0.0;
  return std::make_shared<const StaticBinaryModel>(successes / static_cast<double>(samples.size()));
}

std::shared_ptr<const StaticDurationModel> fit_static_duration(std::span<const DurationSample> samples) {
  std::vector<double> values;
  values.reserve(samples.size());
  double sum = 0;
  for (const auto& s : samples) {
    values.push_back(s.seconds);
    sum += s.seconds;
  }
  const double mean = samples.empty() ? 0.0 : sum / static_cast<double>(samples.size());
  return std::make_shared<const StaticDurationModel>(mean, QuantileTable::from_samples(std::move(values)));
}

OnlineStaticDuration::OnlineStaticDuration(double prior_seconds, double prior_count, std::size_t window)
    : sum_(std::max(0.0, prior_seconds) * std::max(0.0, prior_count)),
      count_(std::max(0.0, prior_count)),
      prior_(std::max(0.0, prior_seconds)),
      window_(std::max<std::size_t>(1, window)) {}

void OnlineStaticDuration::observe(Time, double seconds, bool success) {
  if (!success || !std::isfinite(seconds) || seconds < 0) return;
  sum_ += seconds;
  count_ += 1.0;
  if (recent_.size() < window_)
    recent_.push_back(seconds);
  else
    recent_[seen_ % window_] = seconds;
  ++seen_;
  quantiles_ = QuantileTable::from_samples(recent_);
}

void OnlineStaticDuration::observe_stopped(Time start, double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return;
  observe(start, seconds + expected_seconds(start), true);
}

double OnlineStaticDuration::quantile_seconds(Time, double q) const {
  return recent_.empty() ? prior_ : quantiles_.at(q);
}

}  // namespace rondo::learn
