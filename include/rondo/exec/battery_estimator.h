// What the robot's battery costs, learned from its own readings (docs/executor.md, "Battery").
// Between two readings of Robot::battery() the robot drove some metres, moved, acted, stood idle
// or stood on the charger for some hours; the state of charge dropped by
//
//   from - to = per_metre·m + moving_per_hour·h_moving + acting_per_hour·h_acting
//               + idle_per_hour·h_idle - charging_per_hour·h_charging + noise.
//
// The estimator is Bayesian linear regression on these intervals (recursive least squares in
// information form, with a normal-inverse-gamma prior): it keeps A = V0⁻¹ + Σ x xᵀ,
// b = V0⁻¹ θ0 + Σ x y and the sums for the noise, so the estimate after any set of intervals is
// the same whatever their order (up to rounding), costs O(1) memory, and is deterministic.
//
//   BatteryEstimator e;                       // the prior: BatteryPrior's defaults
//   e.observe(0.90, 0.88, {.metres = 40, .hours_moving = 0.02});
//   BatteryPrediction p = e.predict({.metres = 300, .hours_moving = 0.2, .hours_acting = 0.5});
//   double pessimistic = p.mean + 2 * p.standard_error;
//
// Contract: rates() are clipped at zero (a drain or a charge rate is never negative), so predict()
// is never negative for a plan without charging and grows with every part of the plan.
// standard_error is that of the predicted mean (the rates' uncertainty, with the noise level
// estimated from the residuals); it shrinks as intervals come in. An interval whose end reading
// sits at a clamp (full while charging, or empty) is not learned from: the battery stopped
// following the model there.
#pragma once

#include <array>
#include <cstddef>

namespace rondo::exec {

// What the robot did between two readings.
struct BatteryUse {
  double metres = 0;          // driven along edges crossed
  double hours_moving = 0;    // edge attempts, whether they succeeded or not
  double hours_acting = 0;
  double hours_idle = 0;      // standing off the charger
  double hours_charging = 0;  // on the charger
};

// Fractions of a full battery per metre and per hour.
struct BatteryRates {
  double per_metre = 0;
  double moving_per_hour = 0;
  double acting_per_hour = 0;
  double idle_per_hour = 0;
  double charging_per_hour = 0;
};

// What is believed before the first reading: the rates' means and standard deviations, and the
// noise of one interval's drop (with the weight of `noise_weight` intervals).
struct BatteryPrior {
  BatteryRates mean{.per_metre = 0.0002, .moving_per_hour = 0.2, .acting_per_hour = 0.1, .idle_per_hour = 0.0,
                    .charging_per_hour = 0.5};
  BatteryRates sd{.per_metre = 0.0005, .moving_per_hour = 0.3, .acting_per_hour = 0.2, .idle_per_hour = 0.05,
                  .charging_per_hour = 0.5};
  double noise_sd = 0.005;
  double noise_weight = 2;
};

struct BatteryPrediction {
  double mean = 0;            // expected drop of the state of charge (negative: it charges)
  double standard_error = 0;  // of that mean
};

class BatteryEstimator {
 public:
  static constexpr std::size_t kRates = 5;
  using Vector = std::array<double, kRates>;
  using Matrix = std::array<Vector, kRates>;

  explicit BatteryEstimator(const BatteryPrior& prior = {});

  // Learns from one interval: the state of charge went from `from` to `to` while the robot did
  // `use`. False when it was not learned from (nothing happened, or `to` sits at a clamp).
  bool observe(double from, double to, const BatteryUse& use);

  BatteryRates rates() const;            // the posterior mean, clipped at zero
  BatteryRates standard_errors() const;  // of each rate
  BatteryPrediction predict(const BatteryUse& plan) const;
  // Hours on the charger to go from `from` up to `to` at the learned rate; nothing known: -1.
  double hours_to_charge(double from, double to) const;
  std::size_t observations() const { return n_; }
  double noise_sd() const;  // the estimated noise of one interval's drop

  // The features of an interval, in the order of BatteryRates (charging counts negative).
  static Vector features(const BatteryUse& use);

  // What it has learned, whole (the prior is folded in): kept in the store so that a restarted
  // executor goes on from it (exec::encode_battery_state, src/exec/battery_memory.h).
  struct State {
    Matrix a{};                // V0⁻¹ + Σ x xᵀ
    Vector b{};                // V0⁻¹ θ0 + Σ x y
    double yy = 0;             // θ0ᵀ V0⁻¹ θ0 + Σ y²
    double noise_ss = 0;       // ν0 σ0²
    double noise_weight = 0;   // ν0
    std::size_t n = 0;         // intervals learned from
  };
  State state() const;
  // Goes on from `state`. False, and nothing changes, when it cannot be one this estimator wrote:
  // a value not finite, A not symmetric with a positive diagonal, a negative sum of squares.
  bool restore(const State& state);

 private:
  void solve() const;  // theta_ and covariance_ from A and b, when they changed

  Vector prior_mean_{};
  Matrix a_{};       // V0⁻¹ + Σ x xᵀ
  Vector b_{};       // V0⁻¹ θ0 + Σ x y
  double yy_ = 0;    // θ0ᵀ V0⁻¹ θ0 + Σ y²
  double noise_ss_ = 0;  // ν0 σ0²
  double noise_weight_ = 0;
  std::size_t n_ = 0;
  mutable bool solved_ = false;
  mutable Vector theta_{};
  mutable Matrix covariance_{};  // A⁻¹ (times the noise variance: the rates' covariance)
};

}  // namespace rondo::exec
