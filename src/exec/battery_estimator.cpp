#include "rondo/exec/battery_estimator.h"

#include <algorithm>
#include <cmath>

namespace rondo::exec {
namespace {

using Vector = BatteryEstimator::Vector;
using Matrix = BatteryEstimator::Matrix;
constexpr std::size_t kN = BatteryEstimator::kRates;
// A reading this close to 0 or 1 sits at the clamp: the battery stopped following the model.
constexpr double kClamp = 1e-6;

Vector as_vector(const BatteryRates& r) {
  return {r.per_metre, r.moving_per_hour, r.acting_per_hour, r.idle_per_hour, r.charging_per_hour};
}

BatteryRates as_rates(const Vector& v) {
  return {.per_metre = v[0], .moving_per_hour = v[1], .acting_per_hour = v[2], .idle_per_hour = v[3],
          .charging_per_hour = v[4]};
}

// The inverse of a symmetric positive-definite matrix, through its Cholesky factor L (A = L Lᵀ).
Matrix inverse_spd(const Matrix& a) {
  Matrix l{};
  for (std::size_t i = 0; i < kN; ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      double s = a[i][j];
      for (std::size_t k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
      l[i][j] = i == j ? std::sqrt(std::max(s, 1e-300)) : s / l[j][j];
    }
  }
  Matrix inv{};
  for (std::size_t c = 0; c < kN; ++c) {  // solve L Lᵀ x = e_c
    Vector z{};
    for (std::size_t i = 0; i < kN; ++i) {
      double s = i == c ? 1.0 : 0.0;
      for (std::size_t k = 0; k < i; ++k) s -= l[i][k] * z[k];
      z[i] = s / l[i][i];
    }
    for (std::size_t i = kN; i-- > 0;) {
      double s = z[i];
      for (std::size_t k = i + 1; k < kN; ++k) s -= l[k][i] * inv[k][c];
      inv[i][c] = s / l[i][i];
    }
  }
  return inv;
}

double dot(const Vector& x, const Vector& y) {
  double s = 0;
  for (std::size_t i = 0; i < kN; ++i) s += x[i] * y[i];
  return s;
}

}  // namespace

BatteryEstimator::BatteryEstimator(const BatteryPrior& prior)
    : prior_mean_(as_vector(prior.mean)),
      noise_ss_(prior.noise_weight * prior.noise_sd * prior.noise_sd),
      noise_weight_(prior.noise_weight) {
  // V0 = diag(sd²) / σ0²: the rates' prior covariance in units of the noise variance.
  const Vector sd = as_vector(prior.sd);
  const double noise_var = prior.noise_sd * prior.noise_sd;
  for (std::size_t i = 0; i < kN; ++i) {
    const double precision = noise_var / std::max(sd[i] * sd[i], 1e-300);
    a_[i][i] = precision;
    b_[i] = precision * prior_mean_[i];
    yy_ += precision * prior_mean_[i] * prior_mean_[i];
  }
}

Vector BatteryEstimator::features(const BatteryUse& u) {
  return {u.metres, u.hours_moving, u.hours_acting, u.hours_idle, -u.hours_charging};
}

bool BatteryEstimator::observe(double from, double to, const BatteryUse& use) {
  from = std::clamp(from, 0.0, 1.0);
  to = std::clamp(to, 0.0, 1.0);
  const Vector x = features(use);
  if (dot(x, x) <= 0) return false;                             // nothing happened
  if (to <= kClamp) return false;                                // empty: it may have dropped further
  if (use.hours_charging > 0 && to >= 1 - kClamp) return false;  // full on the charger
  const double y = from - to;
  for (std::size_t i = 0; i < kN; ++i) {
    for (std::size_t j = 0; j < kN; ++j) a_[i][j] += x[i] * x[j];
    b_[i] += x[i] * y;
  }
  yy_ += y * y;
  ++n_;
  solved_ = false;
  return true;
}

void BatteryEstimator::solve() const {
  if (solved_) return;
  covariance_ = inverse_spd(a_);
  for (std::size_t i = 0; i < kN; ++i) theta_[i] = dot(covariance_[i], b_);
  solved_ = true;
}

double BatteryEstimator::noise_sd() const {
  solve();
  // The residual sum of squares (the prior's pull included) is yy - θᵀb at the optimum.
  const double residual = std::max(0.0, yy_ - dot(theta_, b_));
  return std::sqrt((noise_ss_ + residual) / (noise_weight_ + static_cast<double>(n_)));
}

BatteryRates BatteryEstimator::rates() const {
  solve();
  Vector clipped = theta_;
  for (double& r : clipped) r = std::max(r, 0.0);
  return as_rates(clipped);
}

BatteryRates BatteryEstimator::standard_errors() const {
  solve();
  const double s = noise_sd();
  Vector se{};
  for (std::size_t i = 0; i < kN; ++i) se[i] = s * std::sqrt(std::max(covariance_[i][i], 0.0));
  return as_rates(se);
}

BatteryPrediction BatteryEstimator::predict(const BatteryUse& plan) const {
  const Vector x = features(plan);
  const Vector r = as_vector(rates());
  Vector cx{};
  for (std::size_t i = 0; i < kN; ++i) cx[i] = dot(covariance_[i], x);
  return {.mean = dot(x, r), .standard_error = noise_sd() * std::sqrt(std::max(dot(x, cx), 0.0))};
}

BatteryEstimator::State BatteryEstimator::state() const {
  return {.a = a_, .b = b_, .yy = yy_, .noise_ss = noise_ss_, .noise_weight = noise_weight_, .n = n_};
}

bool BatteryEstimator::restore(const State& s) {
  const auto finite = [](double v) { return std::isfinite(v); };
  for (std::size_t i = 0; i < kN; ++i) {
    if (!finite(s.b[i]) || !(s.a[i][i] > 0) || !finite(s.a[i][i])) return false;
    for (std::size_t j = 0; j < kN; ++j)
      if (!finite(s.a[i][j]) || s.a[i][j] != s.a[j][i]) return false;
  }
  if (!finite(s.yy) || s.yy < 0 || !finite(s.noise_ss) || s.noise_ss < 0 || !finite(s.noise_weight) ||
      !(s.noise_weight > 0))
    return false;
  a_ = s.a;
  b_ = s.b;
  yy_ = s.yy;
  noise_ss_ = s.noise_ss;
  noise_weight_ = s.noise_weight;
  n_ = s.n;
  solved_ = false;
  return true;
}

double BatteryEstimator::hours_to_charge(double from, double to) const {
  const double rate = rates().charging_per_hour;
  if (rate <= 0) return -1;
  return std::max(0.0, to - from) / rate;
}

}  // namespace rondo::exec
