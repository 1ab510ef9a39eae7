// FreMEn (Frequency Map Enhancement, Krajnik et al.): a series is its mean plus its strongest
// periodic components, found among the candidate periods one week / k, k = 1..168. This is a
// faithful port of the variant behind the Witham Wharf reference figures (the authors' public
// CFrelement): 32-bit unix seconds, single-precision sums, "spectral balance" (the running sums
// of state·cos/sin minus the same sums for the running mean), a component kept only when 1.5 of
// its periods fit in the training span, prediction mean + 2 Σ amplitude·cos(2π t / period − phase).
//
//   auto model = fit_fremen_binary(flags, {.order = 2});          // clamped to [0.01, 0.99]
//   auto tau = fit_fremen_duration(durations, {.order = 1});      // clamped to >= 0
//   int best = choose_fremen_order(flags, 4);                      // on a time-ordered split
//
// FremenSpectrum is the incremental part (O(168) per sample); solving it for a given order gives
// an immutable FremenComponents snapshot.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/learn/quantile_table.h"
#include "rondo/learn/temporal_model.h"

namespace rondo::learn {

struct FremenOptions {
  int order = 2;  // number of periodic components kept (0 = the mean alone)
};

// A solved FreMEn model: what prediction needs, nothing more.
struct FremenComponents {
  struct Component {
    float period = 0;  // seconds
    float amplitude = 0;
    float phase = 0;  // radians
  };
  float mean = 0.5f;
  std::vector<Component> components;  // strongest first

  // mean + 2 Σ amplitude·cos(2π t / period − phase) at the 32-bit unix second `t`, in float as
  // the reference does, before any clamping.
  float raw_estimate(std::uint32_t t) const;
  Json to_json() const;
  static Result<FremenComponents> from_json(const Json& j);
};

// The running spectral sums of one series. Samples must be added in time order (the training span
// is last − first). Adding costs 168 single-precision sin/cos pairs.
class FremenSpectrum {
 public:
  static constexpr int kCandidates = 168;  // periods of one week / k, k = 1..168
  static constexpr std::int64_t kWeek = 7 * 86400;

  FremenSpectrum();
  void add(std::uint32_t t, float state);
  // The mean and the `order` strongest components. With no samples: mean 0.5 and no components.
  FremenComponents solve(int order) const;
  int count() const { return count_; }

 private:
  struct Bin {
    float period;
    float real_states = 0, imag_states = 0;    // Σ state·cos, Σ state·sin
    float real_balance = 0, imag_balance = 0;  // the same sums for the running mean
  };
  std::vector<Bin> bins_;
  float mean_ = 0;
  int count_ = 0;
  std::int64_t first_ = 0, last_ = 0;
};

// Seconds since the epoch as the reference stores them (32-bit, truncated).
std::uint32_t fremen_seconds(Time t);

class FremenBinaryModel final : public BinaryModel {
 public:
  explicit FremenBinaryModel(FremenComponents c) : c_(std::move(c)) {}
  // The raw estimate clamped to [0.01, 0.99].
  double probability(Time t) const override;
  Json to_json() const override;
  const FremenComponents& components() const { return c_; }

 private:
  FremenComponents c_;
};

// FreMEn of a continuous value. Quantiles are the model's mean plus the empirical quantiles of its
// training residuals (FreMEn itself only predicts a mean).
class FremenDurationModel final : public DurationModel {
 public:
  FremenDurationModel(FremenComponents c, QuantileTable residuals)
      : c_(std::move(c)), residuals_(std::move(residuals)) {}
  double expected_seconds(Time t) const override;
  double quantile_seconds(Time t, double q) const override;
  Json to_json() const override;
  const FremenComponents& components() const { return c_; }
  const QuantileTable& residual_quantiles() const { return residuals_; }

 private:
  FremenComponents c_;
  QuantileTable residuals_;  // of (value − expected) on the training samples; may be negative
};

std::shared_ptr<const FremenBinaryModel> fit_fremen_binary(std::span<const BinarySample> samples,
                                                           FremenOptions options = {});
std::shared_ptr<const FremenDurationModel> fit_fremen_duration(std::span<const DurationSample> samples,
                                                               FremenOptions options = {});

// The order in 0..max_order with the lowest Brier score when fitted on the first
// (1 − validation_fraction) of the samples in time and tested on the rest; 0 for short series.
int choose_fremen_order(std::span<const BinarySample> samples, int max_order, double validation_fraction = 0.25);

// The original authors' de-duplication of training data: keep a sample only if its value differs
// from the last kept one or more than `gap_s` seconds passed since the last kept one. The first
// "last kept value" is false (0), as in the reference. Input in time order.
std::vector<BinarySample> fremen_deduplicate(std::span<const BinarySample> samples, std::int64_t gap_s = 60);

// Online FreMEn: samples are added as they become known, the spectrum is re-solved lazily before
// the next prediction after a change.
class OnlineFremenBinary final : public OnlineBinaryModel {
 public:
  explicit OnlineFremenBinary(int order) : order_(order) {}
  void observe(Time start, Time end, bool value) override;
  double probability(Time t) const override;

 private:
  int order_;
  FremenSpectrum spectrum_;
  mutable FremenComponents solved_;
  mutable bool dirty_ = true;
};

}  // namespace rondo::learn
