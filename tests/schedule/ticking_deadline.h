// A time budget for tests, deterministic: its clock moves on by one tick (a millisecond) at each
// reading, so a solver sees a deadline (seconds_left, as the executor's background budget gives)
// that is a count of its own polls. It also counts the readings made after it said stop: work
// done past the budget.
#pragma once

#include <cstdint>
#include <optional>

#include "rondo/schedule/stop_condition.h"

namespace rondo::schedule::testing {

class TickingDeadline final : public StopCondition {
 public:
  explicit TickingDeadline(std::int64_t ticks) : ticks_(ticks) {}
  bool should_stop() const override {
    const bool stop = ++read_ > ticks_;
    if (stop) ++past_;
    return stop;
  }
  std::optional<double> seconds_left() const override {
    ++read_;
    return static_cast<double>(ticks_ - read_) / 1000.0;
  }
  std::int64_t readings() const { return read_; }
  std::int64_t readings_past_the_deadline() const { return past_; }

 private:
  std::int64_t ticks_;
  mutable std::int64_t read_ = 0;
  mutable std::int64_t past_ = 0;
};

}  // namespace rondo::schedule::testing
