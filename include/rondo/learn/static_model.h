// The static models: one number (the mean of the training samples) for every time of day. The
// baseline every time-dependent model has to beat, and the fallback for series too short to fit.
//
//   auto p = fit_static_binary(flags);          // p->probability(t) == fraction of true samples
//   auto tau = fit_static_duration(durations);  // mean and empirical quantiles, whatever t is
#pragma once

#include <span>
#include <vector>

#include "rondo/learn/quantile_table.h"
#include "rondo/learn/temporal_model.h"

namespace rondo::learn {

class StaticBinaryModel final : public BinaryModel {
 public:
  explicit StaticBinaryModel(double mean) : mean_(mean) {}
  double probability(Time) const override { return mean_; }
  Json to_json() const override;
  double mean() const { return mean_; }

 private:
  double mean_;
};

class StaticDurationModel final : public DurationModel {
 public:
  StaticDurationModel(double mean, QuantileTable quantiles) : mean_(mean), quantiles_(std::move(quantiles)) {}
  double expected_seconds(Time) const override { return mean_; }
  double quantile_seconds(Time, double q) const override { return quantiles_.at(q); }
  Json to_json() const override;
  const QuantileTable& quantiles() const { return quantiles_; }

 private:
  double mean_;
  QuantileTable quantiles_;
};

// The fraction of true samples; 0.5 when there are none.
std::shared_ptr<const StaticBinaryModel> fit_static_binary(std::span<const BinarySample> samples);
// Mean and empirical quantiles; 0 s when there are no samples.
std::shared_ptr<const StaticDurationModel> fit_static_duration(std::span<const DurationSample> samples);

// Online static: the running mean, starting from `prior_count` pseudo-observations of
// `prior_mean` (pass the offline model's mean and sample count to continue from it); 0.5 while
// it has seen nothing at all.
class OnlineStaticBinary final : public OnlineBinaryModel {
 public:
  OnlineStaticBinary(double prior_mean, double prior_count) : sum_(prior_mean * prior_count), count_(prior_count) {}
  void observe(Time, Time, bool value) override {
    sum_ += value ? 1.0 : 0.0;
    count_ += 1.0;
  }
  double probability(Time) const override { return count_ > 0 ? sum_ / count_ : 0.5; }

 private:
  double sum_;
  double count_;
};

// Online static durations: the running mean of the successful samples, starting from
// `prior_count` pseudo-observations of `prior_seconds` (so a handful of samples move it, and a
// single odd one does not take it over); quantiles of the last `window` successful samples, or
// the prior's value alone before the first. Failed attempts say nothing of how long a success
// takes and are ignored. What the executor learns loading and unloading times with.
class OnlineStaticDuration final : public OnlineDurationModel {
 public:
  OnlineStaticDuration(double prior_seconds, double prior_count, std::size_t window = 200);
  void observe(Time start, double seconds, bool success) override;
  // A run stopped after `seconds`, before it ended (right-censored: it would have taken longer).
  // It counts as one run of `seconds` plus the time still expected, taken as the current mean (a
  // memoryless tail: E[T | T > s] = s + mean), so a stopped run raises the estimate above its
  // length instead of holding it at a lower bound.
  void observe_stopped(Time start, double seconds);
  double expected_seconds(Time) const override { return count_ > 0 ? sum_ / count_ : 0.0; }
  double quantile_seconds(Time, double q) const override;
  std::size_t samples() const { return seen_; }  // successful (and stopped) ones observed

 private:
  double sum_;
  double count_;
  double prior_;
  std::size_t window_;
  std::size_t seen_ = 0;
  std::vector<double> recent_;  // a ring of the last `window_` samples
  QuantileTable quantiles_;
};

}  // namespace rondo::learn
