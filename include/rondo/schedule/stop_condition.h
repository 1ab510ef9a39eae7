// When a long computation should give up and return its best answer so far (OMPL's termination
// conditions). Solvers poll `should_stop()` every few thousand steps; they never read a clock.
//
//   DeadlineStop budget(steady_seconds, steady_seconds() + 1.0);   // the caller owns the clock
//   Schedule s = DefaultScheduler{}.solve(problem, budget);
//   AnyStop either({&budget, &cancelled});                         // conditions compose
//
// Contract: should_stop() is cheap (no I/O) and monotone: once it returns true it keeps doing so
// (solvers may stop polling after the first true).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <utility>
#include <vector>

namespace rondo::schedule {

class StopCondition {
 public:
  virtual ~StopCondition() = default;
  virtual bool should_stop() const = 0;
  // Seconds left, when the condition is a time budget: lets a solver that keeps its own clock
  // (CBC) honour the same budget. Nothing when the condition has no notion of time.
  virtual std::optional<double> seconds_left() const { return std::nullopt; }
};

// Never stops: the solver runs to completion (exact solvers prove, heuristics converge).
class NeverStop final : public StopCondition {
 public:
  bool should_stop() const override { return false; }
};

// Stops after a fixed number of polls: deterministic, for tests.
class PollBudgetStop final : public StopCondition {
 public:
  explicit PollBudgetStop(std::int64_t polls) : left_(polls) {}
  bool should_stop() const override { return --left_ < 0; }

 private:
  mutable std::int64_t left_;
};

// Stops at a deadline read from an injected monotonic clock (seconds as a double).
class DeadlineStop final : public StopCondition {
 public:
  DeadlineStop(std::function<double()> now_seconds, double deadline_seconds)
      : now_(std::move(now_seconds)), deadline_(deadline_seconds) {}
  bool should_stop() const override { return now_() >= deadline_; }
  std::optional<double> seconds_left() const override { return deadline_ - now_(); }

 private:
  std::function<double()> now_;
  double deadline_;
};

// Stops as soon as any of its parts does. Does not own the parts.
class AnyStop final : public StopCondition {
 public:
  explicit AnyStop(std::vector<const StopCondition*> parts) : parts_(std::move(parts)) {}
  bool should_stop() const override {
    for (const StopCondition* p : parts_)
      if (p->should_stop()) return true;
    return false;
  }
  std::optional<double> seconds_left() const override {
    std::optional<double> least;
    for (const StopCondition* p : parts_)
      if (auto s = p->seconds_left(); s && (!least || *s < *least)) least = s;
    return least;
  }

 private:
  std::vector<const StopCondition*> parts_;
};

}  // namespace rondo::schedule
