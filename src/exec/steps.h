// The steps of rondo's tasks (rondo/exec/step.h): wait, navigate, act. Each is a small state
// machine; the task run (task_run.h) strings them together.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "monitor.h"
#include "rondo/exec/step.h"
#include "rondo/plan/spec_planner.h"
#include "rondo/traffic/reservations.h"

namespace rondo::exec {

// An early task's wait: until when, whose stop it waits to pass (when another robot's), asked when
// the time comes whether to wait longer (planning around each other: another robot set out for
// the place meanwhile), and told once the robot sets out.
struct EarlyWait {
  Time until{};
  std::string behind{};
  std::function<std::optional<PutOff>()> longer{};
  std::function<void()> set_out{};
};

// Early for a task: waits where the robot is until it is time to leave for the window, or to
// arrive after another robot's stop there.
class WaitStep final : public Step {
 public:
  WaitStep(StepContext& ctx, StepHooks hooks, TaskId task, EarlyWait wait);
  ~WaitStep() override;
  void start() override;
  void halt() override;
  // Stops waiting without reporting an end: the caller decides what happens to the task.
  void abandon();

 private:
  void stop_timer();

  void arm();

  TaskId task_;
  EarlyWait wait_;
  Time since_{};
  TimerId timer_ = 0;
};

// How the robot came to a task's place, for the act step's words: when the journey began, what it
// was expected to take, and where it ended.
class Arrival {
 public:
  virtual ~Arrival() = default;
  virtual Time started() const = 0;
  virtual Duration expected() const = 0;
  virtual map::NodeIndex target() const = 0;
};

// A step that has the robot work (drive, act), watched by a monitor: halting cancels what the
// robot does, and the step ends halted when the robot has answered; a fault holds the monitor.
class RobotStep : public Step {
 public:
  RobotStep(StepContext& ctx, StepHooks hooks) : Step(ctx, std::move(hooks)), monitor_(ctx.clock) {}
  void halt() override;
  void suspend() override { monitor_.suspend(); }
  void resume() override;

 protected:
  virtual void go_on() = 0;  // the robot is free again and no halt is asked: the next command
  // How the step ends once a halt has taken effect: kHalted, unless the step halted itself.
  virtual StepEnd halted_end() { return {.status = StepEnd::Status::kHalted}; }
  bool halting() const { return halting_; }
  Monitor monitor_;

 private:
  bool halting_ = false;
};

// The one way the robot moves (docs/executor.md, "Journeys"): follows the MDP policy edge by edge
// to `target`, re-planning after every edge (so after a failed one); every attempt is the
// executor's to log and learn from. Every journey, a task's or the executor's own (to the dock when
// idle or out of service, to charge), is watched by the navigation monitor, gives up after
// `max_failed_edges` failed attempts, and meets a way found blocked with the blocked-edge policy
// (`blocked_edge`: before leaving, and after a failed edge). A task's journey writes its task's
// events; the executor's own write robot events (`departed`, `arrived`, and the end that the
// executor gives a journey that does not arrive). A task's navigation to its start is recorded
// (NavigationRecord).
class NavigateStep final : public RobotStep, public Arrival {
 public:
  using Purpose = JourneyPurpose;
  // An attempt still running this many times its edge's longest learned attempt (+ the slack) is
  // taken to hang. On the validation runs (Witham Wharf seeds 101-105 and G4S 101-103, 21 days) the
  // slowest successful attempt ran 6.9 and 8.1 times its edge's longest learned one
  // (docs/executor.md, "The window watch").
  static constexpr double kHangFactor = 10;
  NavigateStep(StepContext& ctx, StepHooks hooks, Purpose purpose, std::optional<TaskId> task, map::NodeIndex target);
  ~NavigateStep() override;
  void start() override;
  void on_edge_finished(const EdgeAttempt& attempt) override;

  Time started() const override { return started_; }
  Duration expected() const override { return expected_; }
  map::NodeIndex target() const override { return target_; }
  // What an own journey is for, in its events ("idle: back to the dock").
  const char* errand() const;

 private:
  void go_on() override { advance(); }
  StepEnd halted_end() override;
  void advance();  // the next edge, or the end
  void arrived();
  // Every end of the journey: the way it held ahead is released (the robot stands where it is).
  void finish(StepEnd e);
  void release_way();
  // The traffic manager holds the way ahead for others (docs/traffic.md): the journey waits at its
  // node until told to ask again, or to make way.
  void wait_for_way(map::NodeIndex here);
  void way_wait_ended(const char* how);  // "passed", "made way", "stopped"
  void make_way(const traffic::MakeWay& make_way);
  int rank() const;
  // Sends `route` to the robot; its first edge is the attempt the monitor watches.
  void drive(Route route);
  void note(EventKind kind, const std::string& text);
  // The navigation monitor fired: the task fails, or under the window watch
  // (ExecutorOptions::navigation_window) the journey goes on while the task can still start in its
  // window.
  void overran(const std::string& why);
  // When the window watch lets a journey still running now go on to: the last moment from which
  // the (1 − risk_alpha)-quantile of the way on from the node the robot is heading for still
  // reaches the task's latest start; nothing when that moment is past or the watch is off.
  std::optional<Time> window_open_until() const;
  // When the attempt in progress is taken to hang (ExecutorOptions::navigation_window): past
  // kHangFactor x the longest attempt its edge's learned laws hold (successes, failures and stopped
  // ones, at the attempt's start) + navigation_slack after it began. Nothing without laws.
  std::optional<Time> hangs_at() const;
  // Under the window watch, the monitor runs on to the window's end `until`, or to an earlier moment
  // at which the attempt in progress would be taken to hang.
  void watch_until(Time until);
  // The chance that the attempt in progress, still running now, is one that succeeds, by its
  // edge's learned laws (ExecutorOptions::risk_alpha): of the learned attempts that ran this long,
  // the share of successes, each way weighted by its probability. Nothing without laws, or when no
  // learned attempt ran this long.
  std::optional<double> success_chance(Time now) const;
  std::vector<map::EdgeIndex> expected_route(map::NodeIndex from) const;
  // After a failed edge: why trying again is not worth it (the attempts left are more likely than
  // not all to fail, or the re-planned travel from here would take the navigation past its
  // monitor's limit), or nothing.
  std::optional<std::string> not_worth_trying(const EdgeAttempt& failed) const;
  // Before leaving: when the way crosses an edge held to be blocked and a later departure (before
  // the task's latest start; for an own journey, within a day) is expected to arrive sooner, the
  // end that makes the journey wait for it (ExecutorOptions::BlockedEdge::kWait); nothing otherwise.
  std::optional<StepEnd> leave_later(map::NodeIndex here, Time now) const;

  Purpose purpose_;
  std::optional<TaskId> task_;
  map::NodeIndex target_;
  Time started_{};
  Duration expected_{0};
  Duration offline_expected_{0};
  int failed_edges_ = 0;
  std::optional<map::EdgeIndex> edge_;  // the edge last sent to the robot, and when
  Time edge_since_{};
  double edge_p_ = 1;  // the live model's success probability of that attempt, when it was sent
  bool window_watch_ = false;  // the monitor's limit passed while the window was open
  bool hang_check_ = false;    // the monitor was extended to hangs_at(), not to the window's end
  std::optional<StepEnd> gave_up_;  // an own journey's monitor fired: how it ends once halted
  bool waiting_for_way_ = false;    // held up by another robot's reservation
  // The monitor's time left and words when the wait for the way began: given back when it ends.
  std::optional<Monitor::Limit> before_wait_{};
};

// A spec task's journey (docs/ltl.md): follows the product policy of its formula node by node from
// (node, automaton state), re-planning after every edge, and ends done where the formula is
// satisfied. The policy never sends the robot into a node that would break the formula, whatever
// the map's shortest way. After every node reached, the automaton state is stored with the task's
// progress (TaskBook::set_spec_state): a preempted or interrupted task goes on from it. After a
// failed edge, an edge found blocked (a run of failures the live model did not expect, or the
// attempts left more likely than not all to fail) is held (FoundBlocked) and left out of the
// re-plan, so the way goes round it, or to another node that satisfies the formula. Watched by the
// navigation monitor on the plan's expected time; gives up after `max_failed_edges` failures.
class SpecStep final : public RobotStep, public Arrival {
 public:
  SpecStep(StepContext& ctx, StepHooks hooks, TaskId task);
  void start() override;
  void on_edge_finished(const EdgeAttempt& attempt) override;

  Time started() const override { return started_; }
  Duration expected() const override { return expected_; }
  map::NodeIndex target() const override { return target_; }
  // The edges the product policy expects to take from where the robot is until the formula is
  // satisfied (the dashboard's route); empty when it is, or cannot be.
  std::vector<map::EdgeIndex> planned_route() const;

 private:
  void go_on() override { advance(); }
  void advance();
  // The plan from where the robot is, with the edges held blocked now left out.
  Result<plan::SpecPlan> plan_here(Time now) const;
  // The end of a journey that cannot go on from here: why (naming the nodes that block it).
  void cannot(const plan::SpecPlan& plan, bool held);

  TaskId task_;
  std::uint32_t state_ = 0;
  Time started_{};
  Duration expected_{0};
  map::NodeIndex target_ = 0;
  int failed_edges_ = 0;
  std::optional<map::EdgeIndex> edge_;
};

// At the task's place: runs its actions one after the other, watched by the action monitor. A
// cancel that waited for an interruptible moment takes effect between two actions.
class ActStep final : public RobotStep {
 public:
  ActStep(StepContext& ctx, StepHooks hooks, TaskId task, const Arrival& arrival);
  void start() override;
  void on_action_finished(const ActionResult& result) override;

  Time since() const { return since_; }
  Time expected_end() const { return since_ + expected_; }  // of its actions, as planned
  // The action the robot runs for it now (sent and not answered yet).
  const std::optional<std::string>& running_action() const { return running_; }

 private:
  void go_on() override { run_next(); }
  void run_next();
  Monitor::Limit limit(const TaskRecord& r) const;

  TaskId task_;
  const Arrival& arrival_;
  Time since_{};
  Duration expected_{0};  // the processing time still to spend when it began
  std::size_t index_ = 0;
  std::optional<std::string> running_;
};

}  // namespace rondo::exec
