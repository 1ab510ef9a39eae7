// A robot that a test drives by hand (as BehaviorTree.CPP keeps its test nodes): it records what
// the executor asks of it, and answers only when the test says so, with the outcome the test says.
// Every answer is posted on the clock, as the Robot contract requires, and delivered when the test
// runs the clock.
//
//   ScriptedRobot robot(clock, map, dock);
//   executor.start(); clock.run_until(t);
//   EXPECT_EQ(robot.calls.back(), "drive Dock_Hall +1");   // one committed edge, one on the horizon
//   robot.finish_edge(EdgeOutcome::kFailed, seconds(12));  // the executor re-plans
//   robot.finish_action(ActionOutcome::kSucceeded);
#pragma once

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rondo/exec/clock.h"
#include "rondo/exec/robot.h"
#include "rondo/map/topo_map.h"

namespace rondo::exec::testing {

class ScriptedRobot final : public Robot {
 public:
  ScriptedRobot(Clock& clock, const map::TopoMap& map, map::NodeIndex start)
      : clock_(clock), map_(map), location_(start) {}

  // What the executor asked for, in order: "activate", "drive A_B +2" (the committed edge and the
  // length of the horizon), "act work", "cancel".
  std::vector<std::string> calls;

  void set_listener(RobotListener* listener) override { listener_ = listener; }
  Status activate() override {
    calls.push_back("activate");
    return {};
  }
  void deactivate() override { calls.push_back("deactivate"); }
  map::NodeIndex location() const override { return location_; }
  std::optional<map::Pose> position() const override { return map_.node(location_).pose; }
  bool busy() const override { return edge_.has_value() || action_.has_value(); }
  void drive(const Route& route) override {
    if (busy()) throw std::logic_error("ScriptedRobot::drive while busy");
    if (route.edges.empty() || map_.from_index(route.edges.front()) != location_)
      throw std::logic_error("ScriptedRobot::drive: the route does not leave the robot's location");
    edge_ = route.edges.front();
    started_ = clock_.now();
    calls.push_back(fmt::format("drive {} +{}", map_.edge(*edge_).id, route.edges.size() - 1));
  }
  void run_action(const Action& action, Duration /*expected*/) override {
    if (busy()) throw std::logic_error("ScriptedRobot::run_action while busy");
    action_ = action.name;
    started_ = clock_.now();
    calls.push_back("act " + action.name);
  }
  void cancel() override {
    calls.push_back("cancel");
    if (edge_) finish_edge(EdgeOutcome::kCancelled, clock_.now() - started_);
    if (action_) finish_action(ActionOutcome::kCancelled, "cancelled");
  }
  double battery() const override { return battery_level; }
  bool charging() const override { return on_charger; }
  std::optional<ActionSupport> supported_actions() const override { return actions; }
  std::optional<RobotFault> fault() const override { return fault_; }

  // --- the test's side ---
  double battery_level = 0.9;  // what battery() reads
  std::optional<ActionSupport> actions;  // what supported_actions() says (nothing: any action)
  bool on_charger = false;     // what charging() reads
  bool driving() const { return edge_.has_value(); }
  // A real vehicle may end an attempt anywhere: the next answer leaves the robot at `node`.
  void move_to(map::NodeIndex node) { location_ = node; }
  bool asked(const std::string& call) const { return std::find(calls.begin(), calls.end(), call) != calls.end(); }
  bool acting() const { return action_.has_value(); }
  const std::optional<map::EdgeIndex>& edge() const { return edge_; }

  // Ends the edge being driven with `outcome` after `took`; a success moves the robot to its end.
  void finish_edge(EdgeOutcome outcome, Duration took) {
    if (!edge_) throw std::logic_error("ScriptedRobot::finish_edge: no edge is being driven");
    const EdgeAttempt a{.edge = *edge_, .start = started_, .duration = took, .outcome = outcome};
    if (outcome == EdgeOutcome::kSucceeded) location_ = map_.to_index(*edge_);
    edge_.reset();
    clock_.schedule_at(clock_.now(), [this, a] {
      if (listener_) listener_->on_edge_finished(a);
    });
  }
  void finish_action(ActionOutcome outcome, std::string message = "") {
    if (!action_) throw std::logic_error("ScriptedRobot::finish_action: no action runs");
    const ActionResult r{.name = *action_, .start = started_, .duration = clock_.now() - started_, .outcome = outcome,
                         .message = std::move(message)};
    action_.reset();
    clock_.schedule_at(clock_.now(), [this, r] {
      if (listener_) listener_->on_action_finished(r);
    });
  }
  // The robot sees something (a door: what "door_open", where the door, value 1 open / 0 closed).
  void observe(std::string what, std::string where, double value) {
    const Observation o{.what = std::move(what), .where = std::move(where), .when = clock_.now(), .value = value};
    clock_.schedule_at(clock_.now(), [this, o] {
      if (listener_) listener_->on_observation(o);
    });
  }
  void set_interruptible(bool interruptible) {
    clock_.schedule_at(clock_.now(), [this, interruptible] {
      if (listener_) listener_->on_interruptible_changed(interruptible);
    });
  }
  void report_fault(std::string message) {
    fault_ = RobotFault{.kind = RobotFault::Kind::kError, .message = std::move(message)};
    const RobotFault f = *fault_;
    clock_.schedule_at(clock_.now(), [this, f] {
      if (listener_) listener_->on_fault(f);
    });
  }
  void report_ready() {
    fault_.reset();
    clock_.schedule_at(clock_.now(), [this] {
      if (listener_) listener_->on_ready();
    });
  }

 private:
  Clock& clock_;
  const map::TopoMap& map_;
  RobotListener* listener_ = nullptr;
  map::NodeIndex location_;
  std::optional<map::EdgeIndex> edge_;
  std::optional<std::string> action_;
  std::optional<RobotFault> fault_;
  Time started_{};
};

}  // namespace rondo::exec::testing
