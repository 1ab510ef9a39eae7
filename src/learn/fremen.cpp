#include "rondo/learn/fremen.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "json_util.h"

namespace rondo::learn {
namespace {

// The reference mixes float and double exactly like this; keeping the same mix keeps its figures.
constexpr double kPi = std::numbers::pi;

float binary_clamp(float estimate) {
  return std::clamp(estimate, 0.01f, 0.99f);
}

}  // namespace

std::uint32_t fremen_seconds(Time t) {
  const auto s = std::chrono::floor<std::chrono::seconds>(t).time_since_epoch().count();
  return static_cast<std::uint32_t>(std::clamp<std::int64_t>(s, 0, 0xFFFFFFFFLL));
}

float FremenComponents::raw_estimate(std::uint32_t t) const {
  float estimate = mean;
  const float tf = static_cast<float>(t);
  for (const auto& c : components) {
    // (time / period · 2) in float, then · π and − phase in double, as the reference evaluates it.
    const float cycles_twice = tf / c.period * 2.0f;
    const double angle = static_cast<double>(cycles_twice) * kPi - static_cast<double>(c.phase);
    estimate =
        static_cast<float>(static_cast<double>(estimate) + static_cast<double>(2.0f * c.amplitude) * std::cos(angle));
  }
  return estimate;
}

Json FremenComponents::to_json() const {
  Json comps = Json::array();
  for (const auto& c : components) {
    comps.push_back({{"period", c.period}, {"amplitude", c.amplitude}, {"phase", c.phase}});
  }
  return Json{{"mean", mean}, {"components", comps}};
}

Result<FremenComponents> FremenComponents::from_json(const Json& j) {
  FremenComponents out;
  auto mean = json_number(j, "mean");
  if (!mean) return mean.error();
  out.mean = static_cast<float>(*mean);
  if (!j.contains("components") || !j["components"].is_array()) {
    return Error::invalid("fremen model: 'components' must be an array");
  }
  for (const auto& c : j["components"]) {
    auto period = json_number(c, "period");
    auto amplitude = json_number(c, "amplitude");
    auto phase = json_number(c, "phase");
    if (!period) return period.error();
    if (!amplitude) return amplitude.error();
    if (!phase) return phase.error();
    if (*period <= 0) return Error::invalid("fremen model: a component's period must be > 0");
    out.components.push_back({static_cast<float>(*period), static_cast<float>(*amplitude), static_cast<float>(*phase)});
  }
  return out;
}

FremenSpectrum::FremenSpectrum() {
  bins_.reserve(kCandidates);
  for (int k = 1; k <= kCandidates; ++k) {
    // Integer division, as in the reference: week / 11 is 54981 s, not 54981.8 s.
    bins_.push_back(Bin{static_cast<float>(kWeek / k)});
  }
}

void FremenSpectrum::add(std::uint32_t t, float state) {
  if (count_ == 0) first_ = t;
  last_ = t;
  const float old_mean = mean_;
  mean_ = (mean_ * static_cast<float>(count_) + state) / static_cast<float>(count_ + 1);
  // Keep the balance sums equal to (current mean) · Σ cos/sin. While the mean was 0 they are reset:
  // the reference then forgets the angles of the leading zero samples, and so do we.
  for (auto& b : bins_) {
    if (old_mean > 0) {
      b.real_balance = mean_ * b.real_balance / old_mean;
      b.imag_balance = mean_ * b.imag_balance / old_mean;
    } else {
      b.real_balance = 0;
      b.imag_balance = 0;
    }
  }
  const double tf = static_cast<double>(static_cast<float>(t));
  for (auto& b : bins_) {
    const float angle = static_cast<float>(2.0 * kPi * tf / static_cast<double>(b.period));
    const float c = std::cos(angle);
    const float s = std::sin(angle);
    b.real_states += state * c;
    b.imag_states += state * s;
    b.real_balance += mean_ * c;
    b.imag_balance += mean_ * s;
  }
  ++count_;
}

FremenComponents FremenSpectrum::solve(int order) const {
  FremenComponents out;
  if (count_ == 0) return out;
  out.mean = mean_;
  const auto span = static_cast<int>(last_ - first_);
  std::vector<float> amplitude(bins_.size(), 0.0f);
  for (std::size_t i = 0; i < bins_.size(); ++i) {
    const Bin& b = bins_[i];
    if (1.5 * static_cast<double>(b.period) <= span) {
      const float re = b.real_states - b.real_balance;
      const float im = b.imag_states - b.imag_balance;
      amplitude[i] = std::sqrt(re * re + im * im) / static_cast<float>(count_);
    }
  }
  // The `order` strongest, ties in candidate order (as a stable sort of all would give).
  std::vector<std::size_t> rank(bins_.size());
  for (std::size_t i = 0; i < rank.size(); ++i) rank[i] = i;
  const auto n = static_cast<std::size_t>(std::clamp(order, 0, kCandidates));
  std::partial_sort(
      rank.begin(), rank.begin() + static_cast<std::ptrdiff_t>(n), rank.end(),
      [&](std::size_t a, std::size_t b) { return amplitude[a] != amplitude[b] ? amplitude[a] > amplitude[b] : a < b; });
  for (std::size_t k = 0; k < n && amplitude[rank[k]] > 0; ++k) {
    const Bin& b = bins_[rank[k]];
    const float re = b.real_states - b.real_balance;
    const float im = b.imag_states - b.imag_balance;
    out.components.push_back({b.period, amplitude[rank[k]], std::atan2(im, re)});
  }
  return out;
}

double FremenBinaryModel::probability(Time t) const {
  return static_cast<double>(binary_clamp(c_.raw_estimate(fremen_seconds(t))));
}

Json FremenBinaryModel::to_json() const {
  Json j{{"type", "fremen"}};
  j.update(c_.to_json());
  return j;
}

double FremenDurationModel::expected_seconds(Time t) const {
  return std::max(0.0, static_cast<double>(c_.raw_estimate(fremen_seconds(t))));
}

double FremenDurationModel::quantile_seconds(Time t, double q) const {
  return std::max(0.0, static_cast<double>(c_.raw_estimate(fremen_seconds(t))) + residuals_.at(q));
}

Json FremenDurationModel::to_json() const {
  Json j{{"type", "fremen"}};
  j.update(c_.to_json());
  j["residual_quantiles"] = residuals_.to_json();
  return j;
}

std::shared_ptr<const FremenBinaryModel> fit_fremen_binary(std::span<const BinarySample> samples,
                                                           FremenOptions options) {
  FremenSpectrum spectrum;
  for (const auto& s : samples) spectrum.add(fremen_seconds(s.time), s.value ? 1.0f : 0.0f);
  return std::make_shared<const FremenBinaryModel>(spectrum.solve(options.order));
}

std::shared_ptr<const FremenDurationModel> fit_fremen_duration(std::span<const DurationSample> samples,
                                                               FremenOptions options) {
  FremenSpectrum spectrum;
  for (const auto& s : samples) spectrum.add(fremen_seconds(s.time), static_cast<float>(s.seconds));
  FremenComponents c = spectrum.solve(options.order);
  std::vector<double> residuals;
  residuals.reserve(samples.size());
  for (const auto& s : samples) {
    residuals.push_back(s.seconds - std::max(0.0, static_cast<double>(c.raw_estimate(fremen_seconds(s.time)))));
  }
  return std::make_shared<const FremenDurationModel>(std::move(c),
                                                     QuantileTable::from_samples(std::move(residuals), true));
}

int choose_fremen_order(std::span<const BinarySample> samples, int max_order, double validation_fraction) {
  const auto n = samples.size();
  const auto n_train = static_cast<std::size_t>(std::floor(static_cast<double>(n) * (1.0 - validation_fraction)));
  if (n_train < 2 || n_train >= n) return 0;
  FremenSpectrum spectrum;
  for (std::size_t i = 0; i < n_train; ++i)
    spectrum.add(fremen_seconds(samples[i].time), samples[i].value ? 1.0f : 0.0f);
  int best = 0;
  double best_brier = 0;
  for (int order = 0; order <= max_order; ++order) {
    const FremenBinaryModel model(spectrum.solve(order));
    double brier = 0;
    for (std::size_t i = n_train; i < n; ++i) {
      const double e = model.probability(samples[i].time) - (samples[i].value ? 1.0 : 0.0);
      brier += e * e;
    }
    if (order == 0 || brier < best_brier) {
      best = order;
      best_brier = brier;
    }
  }
  return best;
}

std::vector<BinarySample> fremen_deduplicate(std::span<const BinarySample> samples, std::int64_t gap_s) {
  std::vector<BinarySample> kept;
  bool last_value = false;
  std::int64_t last_time = 0;
  for (const auto& s : samples) {
    const auto t = static_cast<std::int64_t>(fremen_seconds(s.time));
    if (s.value != last_value || t > last_time + gap_s) {
      kept.push_back(s);
      last_value = s.value;
      last_time = t;
    }
  }
  return kept;
}

void OnlineFremenBinary::observe(Time start, Time, bool value) {
  spectrum_.add(fremen_seconds(start), value ? 1.0f : 0.0f);
  dirty_ = true;
}

double OnlineFremenBinary::probability(Time t) const {
  if (dirty_) {
    solved_ = spectrum_.solve(order_);
    dirty_ = false;
  }
  return static_cast<double>(binary_clamp(solved_.raw_estimate(fremen_seconds(t))));
}

}  // namespace rondo::learn
