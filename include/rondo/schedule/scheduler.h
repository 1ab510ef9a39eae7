// The interface every scheduling algorithm implements, so that the executor, the command line
// and the benchmarks can swap them (default, mip, mip-ia).
//
//   std::unique_ptr<Scheduler> s = std::make_unique<DefaultScheduler>();
//   Schedule answer = s->solve(problem, stop);
//
// Contract: solve() never throws on a valid problem (see validate()); it returns its best schedule
// so far when `stop` fires; entries hold every task unless status is kInfeasible or kTimeout, in
// which case entries are empty. Solvers are not thread-safe; use one object per thread.
#pragma once

#include <string_view>

#include "rondo/schedule/problem.h"
#include "rondo/schedule/schedule.h"
#include "rondo/schedule/stop_condition.h"

namespace rondo::schedule {

class Scheduler {
 public:
  virtual ~Scheduler() = default;
  virtual std::string_view name() const = 0;
  // Precondition: validate(problem) succeeded.
  virtual Schedule solve(const Problem& problem, const StopCondition& stop) = 0;
};

}  // namespace rondo::schedule
