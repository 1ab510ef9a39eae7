// Temporal models of navigation experience: the probability of a binary event at a time t (an edge
// crossing succeeds, a door is open) and the distribution of a duration at t (how long crossing takes).
//
//   std::vector<BinarySample> flags = ...;                 // (time, value), any order
//   std::shared_ptr<const BinaryModel> p = fit_fremen_binary(flags, {.order = 2});
//   double p_open = p->probability(*parse_time("2014-09-03T09:00:00Z"));
//   Json saved = p->to_json();                             // binary_model_from_json(saved) reads it back
//
// A fitted model is immutable: share it between threads as std::shared_ptr<const BinaryModel>.
// The online forms (OnlineBinaryModel, OnlineDurationModel) are the mutable companions the executor
// keeps: it tells them every outcome as it becomes known and asks them before every attempt.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/time.h"

namespace rondo::learn {

struct BinarySample {
  Time time;
  bool value = false;
};

struct DurationSample {
  Time time;
  double seconds = 0.0;  // >= 0
};

// The probability that the event happens (the edge crossing succeeds) at time t.
class BinaryModel {
 public:
  virtual ~BinaryModel() = default;
  // Contract: a value in [0, 1] for every t; pure (same t, same answer), safe to call concurrently.
  virtual double probability(Time t) const = 0;
  // A JSON object with a "type" member; binary_model_from_json() (model_json.h) reads it back.
  virtual Json to_json() const = 0;
};

// The distribution of a duration (seconds) at time t.
class DurationModel {
 public:
  virtual ~DurationModel() = default;
  // Contract: finite and >= 0; pure, safe to call concurrently.
  virtual double expected_seconds(Time t) const = 0;
  // The q-quantile for q in (0, 1), >= 0 and non-decreasing in q.
  virtual double quantile_seconds(Time t, double q) const = 0;
  virtual Json to_json() const = 0;
};

// A binary model that keeps learning: observe() each outcome once it is known (in order of the
// time it became known), probability() for the next attempt. Cheap per call; not thread-safe.
class OnlineBinaryModel {
 public:
  virtual ~OnlineBinaryModel() = default;
  // An attempt that started at `start` and ended (its outcome became known) at `end` >= start.
  virtual void observe(Time start, Time end, bool value) = 0;
  virtual double probability(Time t) const = 0;
};

// The online companion of DurationModel.
class OnlineDurationModel {
 public:
  virtual ~OnlineDurationModel() = default;
  virtual void observe(Time start, double seconds, bool success) = 0;
  virtual double expected_seconds(Time t) const = 0;
  virtual double quantile_seconds(Time t, double q) const = 0;
};

using BinaryModelPtr = std::shared_ptr<const BinaryModel>;
using DurationModelPtr = std::shared_ptr<const DurationModel>;

}  // namespace rondo::learn
