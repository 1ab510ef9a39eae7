// The answer of a scheduler: tasks in execution order with their times, the tasks left out with
// a reason each, and the solver's outcome (OMPL style: a status value, not an error).
//
//   Schedule s = DefaultScheduler{}.solve(problem, stop);
//   if (s.status == SolveStatus::kOptimal) ...
//   for (const ScheduledTask& e : s.entries) std::cout << problem.tasks[e.task].id << ' ' << ...;
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/schedule/problem.h"

namespace rondo::schedule {

enum class SolveStatus {
  kOptimal,     // every task scheduled and the objective proved minimal
  kFeasible,    // every task scheduled; not proved optimal (see lower_bound)
  kInfeasible,  // proved: no schedule holds every task
  kTimeout,     // stopped before any schedule of every task was found
};
std::string_view to_string(SolveStatus status);

struct ScheduledTask {
  std::size_t task = 0;  // index into Problem::tasks
  Time depart{};          // leaves the previous place (the previous task's end)
  Time arrival{};          // reaches the start location
  Time start{};           // max(arrival, release)
  Time end{};              // start + duration
  Duration travel{0};
  Duration waiting{0};  // start - arrival
};

// Why a task was left out of a schedule.
enum class DropCause {
  kDoesNotFit,      // no room for it beside the tasks already accepted
  kUnreachable,     // its window cannot be reached from where and when the robot is
  kHigherPriority,  // it does not fit beside higher-priority tasks
  kLowestPriority,  // the lowest priority of the new tasks that did not fit
};

struct DroppedTask {
  std::size_t task = 0;
  std::string reason{};  // for a person, e.g. "dropped for higher-priority tasks A, B"
  DropCause cause = DropCause::kDoesNotFit;
};

struct Schedule {
  SolveStatus status = SolveStatus::kTimeout;
  std::vector<ScheduledTask> entries{};  // execution order
  std::vector<DroppedTask> dropped{};
  Duration objective{0};                  // sum over entries of (end - robot.time)
  std::optional<Duration> lower_bound{};    // proved bound on the optimum, when the solver has one
  std::optional<Time> return_arrival{};    // when Problem::return_to is set
  double seconds = 0;                     // filled by callers that measure time (CLI, bench)

  std::vector<std::size_t> order() const;
  // (objective - bound) / objective, when a bound is known.
  std::optional<double> gap() const;
};

// Times a given order from the robot's state: leave at once, wait at the start location until the
// release. An error naming the first task that misses its latest start (or the return deadline).
// Item and precedence rules are not checked here (see check_schedule).
Result<Schedule> time_order(const Problem& problem, const std::vector<std::size_t>& order);

}  // namespace rondo::schedule
