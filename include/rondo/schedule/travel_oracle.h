// Expected travel durations between dense location indices, possibly depending on the departure
// time. The scheduler only sees this interface; the planner's TravelOracle plugs in through an
// adapter later. A matrix implementation serves files, tests and benchmarks.
//
//   auto travel = std::make_shared<MatrixTravel>(3, std::vector<Duration>{...9 entries...});
//   Duration d = travel->travel(0, 2, depart_at);
//
// Contract for every implementation:
// - travel(a, b, t) >= lower_bound(a, b) >= 0 for every t;
// - FIFO: t1 <= t2 implies t1 + travel(a, b, t1) <= t2 + travel(a, b, t2) (leaving later never
//   arrives earlier), so waiting before departure never helps and solvers may leave at once;
// - deterministic and free of side effects (solvers call it from many places, in any order).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo::schedule {

using LocationIndex = std::size_t;

class TravelOracle {
 public:
  virtual ~TravelOracle() = default;
  // Number of locations: valid indices are 0 .. location_count() - 1.
  virtual std::size_t location_count() const = 0;
  virtual Duration travel(LocationIndex from, LocationIndex to, Time depart) const = 0;
  // A lower bound over all departure times (the static value for static oracles).
  virtual Duration lower_bound(LocationIndex from, LocationIndex to) const = 0;
  // True when travel() ignores the departure time: solvers then cache a matrix.
  virtual bool time_dependent() const = 0;
};

// A static, possibly asymmetric matrix (row = from). The triangle inequality is not assumed.
class MatrixTravel final : public TravelOracle {
 public:
  // `row_major` has size*size non-negative entries; an error otherwise.
  static Result<MatrixTravel> create(std::size_t size, std::vector<Duration> row_major);

  std::size_t location_count() const override { return size_; }
  Duration travel(LocationIndex from, LocationIndex to, Time) const override { return at(from, to); }
  Duration lower_bound(LocationIndex from, LocationIndex to) const override { return at(from, to); }
  bool time_dependent() const override { return false; }
  Duration at(LocationIndex from, LocationIndex to) const { return matrix_[from * size_ + to]; }

 private:
  MatrixTravel(std::size_t size, std::vector<Duration> m) : size_(size), matrix_(std::move(m)) {}
  std::size_t size_ = 0;
  std::vector<Duration> matrix_{};
};

// Travel that changes with the time of departure: matrices given at increasing breakpoints,
// linearly interpolated between them and constant outside. FIFO holds when no entry falls faster
// than real time between two breakpoints (slope >= -1); create() checks that.
class PiecewiseLinearTravel final : public TravelOracle {
 public:
  struct Breakpoint {
    Time at{};
    std::vector<Duration> row_major{}; // size*size entries
  };
  static Result<PiecewiseLinearTravel> create(std::size_t size, std::vector<Breakpoint> breakpoints);

  std::size_t location_count() const override { return size_; }
  Duration travel(LocationIndex from, LocationIndex to, Time depart) const override;
  Duration lower_bound(LocationIndex from, LocationIndex to) const override {
    return lower_[from * size_ + to];
  }
  bool time_dependent() const override { return true; }

 private:
  PiecewiseLinearTravel() = default;
  std::size_t size_ = 0;
  std::vector<Breakpoint> points_{};
  std::vector<Duration> lower_{};
};

}  // namespace rondo::schedule
