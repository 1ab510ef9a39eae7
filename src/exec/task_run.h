// One task in progress, as the sequence of its steps: [wait] -> navigate to its place -> act ->
// [navigate to its end place]. The run decides what a halted step means (a cancel, a preemption,
// an overrun), holds back a monitor or a cancel while the task cannot be interrupted, and reports
// the task's end once to the executor, which writes it to the book.
//
//   TaskRun run(ctx, id, wait_until, [&](TaskRun::End e) { ... });
//   run.start();
//   run.stop(TaskRun::Stop::kPreempt, Outcome::kOutranked, "outranked by ...");
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "steps.h"

namespace rondo::exec {

class TaskRun {
 public:
  enum class Stop { kNone, kOverrun, kCancel, kPreempt };
  using End = TaskEnd;

  // `wait`: early, so it first waits where the robot is (WaitStep).
  TaskRun(StepContext& ctx, TaskId id, std::optional<EarlyWait> wait, std::function<void(End)> ended);
  TaskRun(const TaskRun&) = delete;
  TaskRun& operator=(const TaskRun&) = delete;

  void start();
  const TaskId& id() const { return id_; }
  const Task& task() const { return ctx_.book.at(id_).task; }
  // Still waiting for its window: to the scheduler it is a pending task, not a running one.
  bool waiting() const { return current() == wait_; }
  // Since when it acts at its place, and when its actions are expected to end, while it does.
  std::optional<Time> acting_since() const;
  // When this run began (start()): a task run again after a preemption or a retry has a run each.
  Time run_since() const { return run_since_; }
  std::optional<Time> acting_until() const;
  // The action the robot runs for it now, while it acts.
  std::optional<std::string> running_action() const;
  // The task allows it, and the robot says it may be interrupted now.
  bool interruptible() const { return task().interruptible && robot_interruptible_; }
  Step* current() const { return index_ < steps_.size() ? steps_[index_].get() : nullptr; }

  // Ends the task through its current step. A preemption or a cancel already under way is not
  // replaced by another stop, except that a cancel replaces a preemption or an overrun.
  void stop(Stop why, Outcome outcome, std::string reason);
  // A cancel while the task cannot be interrupted: done at its next interruptible moment, or
  // between two actions.
  bool stopping() const { return stop_ != Stop::kNone; }
  Stop stop_kind() const { return stop_; }
  void cancel_when_possible(std::string reason) { cancel_pending_ = std::move(reason); }
  // Precondition: waiting(). Stops waiting with no end reported; the executor decides the rest.
  void abandon_wait();
  // The robot says whether it may be interrupted now. True when that let something held back
  // happen (a pending cancel, a monitor that fired meanwhile).
  bool set_robot_interruptible(bool interruptible);

 private:
  void next_step();
  void step_ended(StepEnd end);
  void overrun(Outcome outcome, const std::string& reason);
  bool stop_here();
  StepHooks hooks();
  void finish(End end);

  StepContext& ctx_;
  TaskId id_;
  Time run_since_{};
  std::function<void(End)> ended_;
  std::vector<std::unique_ptr<Step>> steps_;
  std::size_t index_ = 0;
  WaitStep* wait_ = nullptr;
  ActStep* act_ = nullptr;
  bool robot_interruptible_ = true;
  Stop stop_ = Stop::kNone;
  Outcome stop_outcome_ = Outcome::kNone;
  std::string stop_reason_;
  std::optional<std::string> cancel_pending_;
  std::optional<std::pair<Outcome, std::string>> overrun_held_;  // fired while not interruptible
  StepEnd done_{};  // what the act step said when it finished
  bool finished_ = false;
};

}  // namespace rondo::exec
