// What the planner asks of one edge, online: the success probability and the traversal time
// distribution at a time t, given everything observed on the edge so far.
//
//   std::unique_ptr<EdgePredictor> edge = ...;            // from a fitted model set
//   double p = edge->probability(t);
//   edge->observe({.start = t, .end = t + seconds(12), .seconds = 12.0, .success = true});
//
// An EdgePredictor is mutable and single-threaded: the executor owns one per edge. The immutable,
// shareable part (the fitted models) sits behind it.
#pragma once

#include <memory>

#include "rondo/core/time.h"

namespace rondo::learn {

// One traversal attempt as the models see it.
struct Attempt {
  Time start;
  Time end;            // start + duration: when the outcome became known
  double seconds = 0;  // the duration
  bool success = false;
};

class EdgePredictor {
 public:
  virtual ~EdgePredictor() = default;
  // Records an attempt whose outcome is now known. Contract: attempts arrive in order of `end`.
  virtual void observe(const Attempt& attempt) = 0;
  // P(an attempt starting at t succeeds), in [0, 1].
  virtual double probability(Time t) const = 0;
  // Expected duration of an attempt starting at t, seconds >= 0.
  virtual double expected_seconds(Time t) const = 0;
  // Its q-quantile, q in (0, 1), non-decreasing in q.
  virtual double quantile_seconds(Time t, double q) const = 0;
};

}  // namespace rondo::learn
