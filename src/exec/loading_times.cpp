#include "loading_times.h"

#include <algorithm>
#include <cmath>

namespace rondo::exec {

bool LoadingTimes::learns(const std::string& action) const {
  return std::find(actions_.begin(), actions_.end(), action) != actions_.end();
}

learn::OnlineStaticDuration& LoadingTimes::model(const std::string& action, const std::string& place,
                                                 Duration declared) {
  auto it = models_.find({action, place});
  if (it == models_.end())
    it = models_.emplace(std::pair{action, place}, learn::OnlineStaticDuration(to_seconds(declared), kPriorCount))
             .first;
  return it->second;
}

void LoadingTimes::add_ratio(double ratio) {
  if (!std::isfinite(ratio) || ratio < 0) return;
  if (ratios_.size() < kRatioWindow)
    ratios_.push_back(ratio);
  else
    ratios_[ratios_seen_ % kRatioWindow] = ratio;
  ++ratios_seen_;
  ratio_quantiles_ = learn::QuantileTable::from_samples(ratios_);
}

void LoadingTimes::observe(const std::string& action, const std::string& place, Duration declared, Duration took,
                           bool success, Time at) {
  if (!learns(action)) return;
  learn::OnlineStaticDuration& m = model(action, place, declared);
  if (const double before = m.expected_seconds(at); success && before > 0) add_ratio(to_seconds(took) / before);
  m.observe(at, to_seconds(took), success);
}

// As the model learns it (E[T | T > s] = s + mean): so does the pooled ratio.
void LoadingTimes::observe_stopped(const std::string& action, const std::string& place, Duration declared,
                                   Duration took, Time at) {
  if (!learns(action)) return;
  learn::OnlineStaticDuration& m = model(action, place, declared);
  if (const double before = m.expected_seconds(at); before > 0) add_ratio((to_seconds(took) + before) / before);
  m.observe_stopped(at, to_seconds(took));
}

Duration LoadingTimes::expected(const std::string& action, const std::string& place, Duration declared) const {
  const auto it = models_.find({action, place});
  if (it == models_.end() || it->second.samples() == 0) return declared;
  return from_seconds(it->second.expected_seconds(Time{}));
}

std::optional<Duration> LoadingTimes::quantile(const std::string& action, const std::string& place, Duration declared,
                                               double q) const {
  if (ratios_.size() < kRatioSamples) return std::nullopt;
  return from_seconds(to_seconds(expected(action, place, declared)) * ratio_quantiles_.at(q));
}

std::vector<LearnedActionTime> LoadingTimes::entries() const {
  std::vector<LearnedActionTime> out;
  for (const auto& [key, model] : models_)
    out.push_back({.action = key.first, .place = key.second, .expected_seconds = model.expected_seconds(Time{}),
                   .samples = model.samples()});
  return out;
}

}  // namespace rondo::exec
