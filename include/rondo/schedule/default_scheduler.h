// rondo's own scheduler (issue 5): exact on small problems, anytime on large ones.
//
//   DefaultScheduler solver({.seed = 7});
//   Schedule s = solver.solve(problem, stop);   // kOptimal when the dynamic program finished
//
// How (docs/scheduling.md has the details and the proofs):
// 1. a restricted dynamic program (beam over partial sequences with Pareto labels) builds a
//    first schedule;
// 2. local search (segment relocation, O(1) rejection of infeasible moves by forward slack,
//    objective change by delay propagation that stops where the old times resume) and iterated
//    perturbation improve it until `stop`;
// 3. for up to `exact_max_tasks` tasks, a label-setting dynamic program over (visited set, last
//    task) with time/cost dominance, window elimination and a sum-of-release-times lower bound
//    proves the optimum or infeasibility, unless it exceeds `exact_max_labels` or `stop` fires.
// Time-dependent travel, precedence, capacity and same-looking items are respected throughout.
#pragma once

#include <cstddef>
#include <cstdint>

#include "rondo/schedule/scheduler.h"

namespace rondo::schedule {

struct DefaultSchedulerOptions {
  std::uint64_t seed = 1;
  std::size_t exact_max_tasks = 63;        // larger problems are never attempted exactly
  std::size_t exact_max_labels = 2000000;  // per stage of the exact dynamic program (~100 MB)
  std::size_t first_beam_width = 32;
  std::size_t max_beam_width = 4096;
  bool improve = true;  // local search; off = construction only (for tests of the parts)
};

class DefaultScheduler final : public Scheduler {
 public:
  explicit DefaultScheduler(DefaultSchedulerOptions options = {}) : options_(options) {}
  std::string_view name() const override { return "default"; }
  Schedule solve(const Problem& problem, const StopCondition& stop) override;

 private:
  DefaultSchedulerOptions options_;
};

}  // namespace rondo::schedule
