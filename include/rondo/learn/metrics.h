// Scores of probabilistic predictions, accumulated one prediction at a time.
//
//   BinaryScore s;  s.add(0.9, true);  s.add(0.2, false);
//   s.brier();          // mean (p − y)²
//   DurationScore d;  d.add({.expected = 10, .median = 9, .q90 = 14}, /*truth*/ 12);
//   d.mae(); d.rmse(); d.pinball();
//
// Each loss is paired with the point forecast it rewards: MAE with the median, RMSE with the
// mean (expected value); mae_of_mean() is also kept, for readers who want the mean's MAE.
#pragma once

#include <cmath>

namespace rondo::learn {

class BinaryScore {
 public:
  void add(double p, bool truth) {
    const double y = truth ? 1.0 : 0.0;
    squared_ += (p - y) * (p - y);
    wrong_ += ((p >= 0.5) != truth) ? 1.0 : 0.0;
    ++count_;
  }
  double brier() const { return count_ ? squared_ / count_ : 0.0; }
  double rmse() const { return std::sqrt(brier()); }
  // The fraction of predictions on the wrong side of 0.5 (p = 0.5 counts as "true").
  double error_rate() const { return count_ ? wrong_ / count_ : 0.0; }
  double count() const { return count_; }

 private:
  double squared_ = 0, wrong_ = 0, count_ = 0;
};

class DurationScore {
 public:
  static constexpr double kLevel = 0.9;  // the quantile level of the pinball loss

  struct Forecast {
    double expected = 0;
    double median = 0;
    double q90 = 0;
  };
  void add(const Forecast& f, double truth) {
    abs_ += std::fabs(f.median - truth);
    abs_mean_ += std::fabs(f.expected - truth);
    squared_ += (f.expected - truth) * (f.expected - truth);
    pinball_ += truth >= f.q90 ? kLevel * (truth - f.q90) : (1 - kLevel) * (f.q90 - truth);
    ++count_;
  }
  // Mean absolute error of the median forecast.
  double mae() const { return count_ ? abs_ / count_ : 0.0; }
  double mae_of_mean() const { return count_ ? abs_mean_ / count_ : 0.0; }
  double rmse() const { return count_ ? std::sqrt(squared_ / count_) : 0.0; }
  // Mean pinball loss of the 0.9-quantile.
  double pinball() const { return count_ ? pinball_ / count_ : 0.0; }
  double count() const { return count_; }

 private:
  double abs_ = 0, abs_mean_ = 0, squared_ = 0, pinball_ = 0, count_ = 0;
};

}  // namespace rondo::learn
