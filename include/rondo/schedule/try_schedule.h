// Adding tasks to a day (MISSION.md §3, trySchedule/drop): schedule the old and new tasks
// together; when no schedule holds them all, drop the lowest-priority new tasks and try again,
// with the preemption signal for an interruptible running task. Every dropped task gets a reason.
//
//   TryScheduleRequest r{problem, /*new_tasks=*/{5, 6, 7}, RunningTask{"patrol", 1, true}};
//   TryScheduleResult out = try_schedule(r, solver, stop, rng);
//   if (out.preempt_running) { interrupt it, add it back as a new task, call again; }
//   for (const DroppedTask& d : out.schedule.dropped) log(problem.tasks[d.task].id, d.reason);
//
// Contract: the problem's robot state is where and when the robot is free (after the running task
// ends, if one runs); old tasks (those not in new_tasks) are never dropped: if they cannot all be
// scheduled the outcome is kOldTasksInfeasible. Deterministic for a given rng state.
#pragma once

#include <cstddef>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "rondo/core/timezone.h"
#include "rondo/schedule/scheduler.h"

namespace rondo::schedule {

struct RunningTask {
  std::string id;
  int priority = 0;
  bool interruptible = true;
};

enum class DropPolicy {
  // The paper: drop the lowest-priority 20 % of the remaining new tasks (at least one, ties at
  // random) until a schedule exists.
  kPaper,
  // The paper's rule, then give back every dropped task that fits, highest priority first. It
  // drops a subset of what the paper drops (never more tasks, never a higher priority instead).
  kPaperThenRestore,
};

struct TryScheduleRequest {
  Problem problem;
  std::vector<std::size_t> new_tasks;  // indices into problem.tasks
  std::optional<RunningTask> running{};
  // New tasks that may be dropped but never preempt the running task, whatever their priority
  // (tasks offered again after an earlier drop).
  std::vector<std::size_t> cannot_preempt{};
  // The zone that times in drop reasons are given in (TimeZone::format_clock); UTC by default.
  TimeZone zone = TimeZone::utc();
  DropPolicy policy = DropPolicy::kPaperThenRestore;
};

enum class TryScheduleOutcome {
  kAllScheduled,
  kSomeDropped,
  kPreemptRunning,       // interrupt the running task, add it back as new, and call again
  kOldTasksInfeasible,   // even with every new task dropped, the old tasks do not fit
};

struct TryScheduleResult {
  TryScheduleOutcome outcome = TryScheduleOutcome::kAllScheduled;
  Schedule schedule;                 // of the kept tasks; `dropped` holds the others with reasons
  std::string preempt_reason;        // when outcome == kPreemptRunning
  int attempts = 0;                  // solver calls
};

TryScheduleResult try_schedule(const TryScheduleRequest& request, Scheduler& solver, const StopCondition& stop,
                               std::mt19937_64& rng);

}  // namespace rondo::schedule
