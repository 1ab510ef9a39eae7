// A step: one thing a task does, as a small state machine driven by robot events (after
// BehaviorTree.CPP's stateful action nodes). A task is a sequence of steps (exec::TaskRun): wait
// for its window, navigate to its place, act, navigate to its end place; later issues add pick up,
// drop, charge and wait-for-a-door. A step owns its timers and its monitor; it changes the task's
// state only through the task book, and reports its end once, through its hooks.
//
//   NavigateStep go(ctx, hooks, NavigateStep::Purpose::kToStart, task_id, target);
//   go.start();                    // later: hooks.ended({kDone}) on arrival
//   go.on_edge_finished(attempt);  // the executor forwards the robot's answers
//   go.halt();                     // ends kHalted once the robot has stopped (maybe at once)
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/timezone.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor_types.h"
#include "rondo/exec/outcome.h"
#include "rondo/exec/robot.h"
#include "rondo/exec/task_book.h"
#include "rondo/learn/robot_speeds.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/edge_model_view.h"

namespace rondo::plan {
class TravelPlanner;
}

namespace rondo::exec {

class TravelCache;
class TrafficLink;
class FoundBlocked;
class SpecTasks;

// What a journey (exec::NavigateStep) is for: a task's way to its place or to its end place; the
// executor's own way to the dock when idle, when out of service, or to charge.
// kMakeWay: parked (idle, or waiting for a task's window) on a node another robot needs, it moves
// aside where the traffic manager sends it (docs/traffic.md).
enum class JourneyPurpose { kToStart, kToEnd, kDock, kOutOfService, kCharge, kMakeWay };

// How a step ended.
struct StepEnd {
  enum class Status {
    kDone,     // it did what it is for
    kFailed,   // it cannot: `outcome` and `reason` say why
    kHalted,   // halt() was asked, or the robot stopped it: the task run decides what that means
    kBlocked,  // it cannot now (the way is blocked): the task may wait and be scheduled again
  };
  Status status = Status::kDone;
  Outcome outcome = Outcome::kNone;
  std::string reason{};
  std::optional<map::EdgeIndex> edge{};  // kBlocked, or kFailed for no route now: the edge found blocked
  std::optional<Time> not_before{};      // kBlocked before leaving: the departure expected to arrive soonest
};

// How a task's run ended: a final state, or back to the queue (preempted).
struct TaskEnd {
  bool requeue = false;
  TaskState state = TaskState::kSucceeded;
  Outcome outcome = Outcome::kNone;
  std::string reason{};
  std::optional<map::EdgeIndex> edge{};  // requeued because this edge was found blocked
  std::optional<Time> not_before{};      // and not to leave before this (StepEnd::not_before)
};

// How a step talks back to whoever runs it (a task run, or the executor for its own trips).
struct StepHooks {
  std::function<void(StepEnd)> ended;                                // exactly once
  std::function<void(Outcome, const std::string&)> overrun;          // its monitor fired
  std::function<bool()> stop_here = [] { return false; };            // asked between two actions
};

// What a step works with. The executor owns all of it, and it outlives every step.
struct StepContext {
  Clock& clock;
  Robot& robot;
  const map::TopoMap& map;
  TaskBook& book;
  const TravelCache& travel;
  const TravelCache& offline_travel;  // the nightly snapshot alone (NavigationRecord::offline_expected)
  plan::TravelPlanner& planner;
  const ExecutorOptions& options;
  const TimeZone& zone;
  ExecutorStats& stats;
  std::vector<NavigationRecord>& navigations;
  const bool& in_fault;  // the robot reports a fault: steps send nothing new to it
  const plan::EdgeModelView& models;  // what the planner reads (the live model, when online)
  std::function<void()> before_command;  // called just before every drive() and run_action()
  // What journeys found of the edges (failures in a row, edges held blocked), known to every journey.
  FoundBlocked& found_blocked;
  const SpecTasks& specs;  // spec tasks' automata and product plans
  const learn::RobotSpeeds& speeds;  // the robots' paces (Building::speeds): `travel` is in standard time
  TrafficLink* traffic = nullptr;    // the way reserved ahead (docs/traffic.md); null: the robot moves freely

  std::string clock_text(Time t) const { return zone.format_clock(t); }
  // A standard travel time (`travel`'s) as this robot takes it.
  Duration own(Duration standard) const;
};

class Step {
 public:
  Step(StepContext& ctx, StepHooks hooks) : ctx_(ctx), hooks_(std::move(hooks)) {}
  virtual ~Step() = default;
  Step(const Step&) = delete;
  Step& operator=(const Step&) = delete;

  // Begins the step. It may end at once (hooks.ended called from inside start()).
  virtual void start() = 0;
  // Stops it: the step ends kHalted once the robot has answered, or at once when the robot is not
  // working for it.
  virtual void halt() = 0;
  virtual void on_edge_finished(const EdgeAttempt&) {}
  virtual void on_action_finished(const ActionResult&) {}
  // A robot fault: monitors stand still (suspend) and run on with the time they had left, and
  // the step goes on from where the robot is (resume).
  virtual void suspend() {}
  virtual void resume() {}

 protected:
  void end(StepEnd e) {
    if (ended_) return;
    ended_ = true;
    hooks_.ended(std::move(e));
  }
  void end_silently() { ended_ = true; }  // stopped by its owner, who needs no report
  bool ended() const { return ended_; }

  StepContext& ctx_;
  StepHooks hooks_;

 private:
  bool ended_ = false;
};

}  // namespace rondo::exec
