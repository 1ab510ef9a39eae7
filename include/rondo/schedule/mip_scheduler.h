// The published baseline (MISSION.md §2): the big-M disjunctive mixed-integer program of the
// integrated-control paper, solved with COIN-OR CBC.
//
//   MipScheduler mip({.interval_algebra = true, .time_limit = seconds(10)});
//   Schedule s = mip.solve(problem, stop);
//
// Model: continuous start s_i in [r_i, latest_i]; end e_i = s_i + p_i; one binary y_jk per pair
// (j < k): y_jk = 1 means j before k;
//   s_j + p_j + E(j,k) <= s_k + M_jk (1 - y_jk)   and   s_k + p_k + E(k,j) <= s_j + M_kj y_jk;
//   s_i >= robot.time + E(robot, i); minimise sum of e_i.
// E is read at the robot's time (the paper reads travel at departure; a time-dependent oracle is
// therefore only approximated here, and the returned schedule is re-timed exactly).
// The interval-algebra variant fixes y_jk where the windows allow only one order, and `after`
// precedences (pickup before drop included) fix their pair in both variants. Capacity and
// same-looking items are not in the paper's model: such problems are refused (kUnsupported error
// from check_supported; solve() then returns kTimeout with no entries).
#pragma once

#include <string>

#include "rondo/core/result.h"
#include "rondo/schedule/scheduler.h"

namespace rondo::schedule {

struct MipOptions {
  bool interval_algebra = false;
  Duration time_limit = seconds(10);  // also bounded by stop.seconds_left()
};

class MipScheduler final : public Scheduler {
 public:
  explicit MipScheduler(MipOptions options = {}) : options_(options) {}
  std::string_view name() const override { return options_.interval_algebra ? "mip-ia" : "mip"; }
  Schedule solve(const Problem& problem, const StopCondition& stop) override;
  // Whether the model can express the problem (no capacity, no same-looking items, no return).
  static Status check_supported(const Problem& problem);
  // Pairs fixed before solving in the last solve (interval algebra + precedence).
  std::size_t fixed_pairs() const { return fixed_pairs_; }

 private:
  MipOptions options_;
  std::size_t fixed_pairs_ = 0;
};

}  // namespace rondo::schedule
