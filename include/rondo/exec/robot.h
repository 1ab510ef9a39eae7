// The robot as the executor sees it (DESIGN.md, Robot interface). The simulator (sim::SimRobot),
// the VDA 5050 adapter and every other real adapter implement it; the executor cannot tell them
// apart.
//
//   robot.set_listener(&executor);
//   robot.activate();                       // connect; a fault until the robot is ready
//   robot.drive({.edges = {e1, e2, e3}, .committed = 1});   // later: on_edge_finished({e1, ...})
//   robot.run_action(action, minutes(2));   // later: listener->on_action_finished({...})
//   robot.cancel();                         // the running edge or action ends as cancelled
//
// Contract:
// - One thing at a time: drive() and run_action() are only called when !busy().
// - drive() takes a route of consecutive edges from location(). The robot drives the first
//   `committed` edges, one on_edge_finished() each, and stops at the end of them; the rest is the
//   horizon: where the executor expects to go next, which a vehicle may plan with (VDA 5050's
//   unreleased nodes) but never drives before it is committed by a later drive(). busy() is true
//   until the callback of the last committed edge, or of the first one that did not succeed (the
//   rest is then not driven). After that the executor may call drive() again from the node the
//   robot is at, which continues the same journey (for VDA 5050: an order update).
// - Every edge and every run_action() is answered by exactly one callback, never from inside the
//   call itself (the robot posts it to the executor's clock), also after cancel().
// - Callbacks arrive on the executor's clock thread: an adapter with threads of its own hands them
//   over with Clock::post().
// - Where the robot is after an attempt is location(): the simulator stays at the edge's start
//   node after a failed or cancelled edge (MISSION.md §4), but a real vehicle may stop anywhere,
//   so the executor always asks. position() is the metric pose, when the robot reports one.
// - A fault (a robot-level error, a lost connection) is reported with on_fault() and its end with
//   on_ready(). While in fault the executor dispatches nothing new and its monitors stand still.
//   An edge that a fault interrupted ends with the outcome kRobotFault: it says nothing about the
//   way, so it is not learning data.
// - Times are the executor's clock: the robot reads the same Clock.
// - A robot that knows which actions it can run says so (supported_actions()); the answer may
//   come later (a vehicle's factsheet arrives after it connects).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/task.h"
#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"

namespace rondo::exec {

// How one attempt to cross one edge ended.
enum class EdgeOutcome {
  kSucceeded,   // at the edge's end node
  kFailed,      // the way was blocked: the robot gave up on this edge
  kCancelled,   // ended by cancel(): says nothing about the way
  kRobotFault,  // ended by a fault of the robot or its connection: says nothing about the way
};
const char* to_string(EdgeOutcome outcome);
// Only succeeded and failed attempts are experience of the way (the traversal log, the models).
constexpr bool is_learning_data(EdgeOutcome o) { return o == EdgeOutcome::kSucceeded || o == EdgeOutcome::kFailed; }

// One attempt to cross one edge: the experience the models learn from.
struct EdgeAttempt {
  map::EdgeIndex edge = 0;
  Time start{};
  Duration duration{0};
  EdgeOutcome outcome = EdgeOutcome::kSucceeded;
  std::string message{};  // the robot's words, for the event log; may be empty

  bool succeeded() const { return outcome == EdgeOutcome::kSucceeded; }
};

// A journey handed to the robot: `edges` from location(), consecutive; the first `committed` of
// them are released to be driven (1 <= committed <= edges.size()), the rest is the horizon.
struct Route {
  std::vector<map::EdgeIndex> edges;
  std::size_t committed = 1;
};

enum class ActionOutcome { kSucceeded, kFailed, kCancelled, kRobotFault };
const char* to_string(ActionOutcome outcome);

struct ActionResult {
  std::string name{};  // the action's name, as given to run_action()
  Time start{};
  Duration duration{0};
  ActionOutcome outcome = ActionOutcome::kSucceeded;
  std::string message{};  // why it failed, for the event log; may be empty
};

// Something seen of the building: by the robot on its way (RobotListener::on_observation), or by
// the building's own sensors (Executor::observe): a door open or closed, a person present.
struct Observation {
  // The kinds the executor knows; any other kind is stored and not acted on.
  static constexpr std::string_view kDoorOpen = "door_open";            // where: a door (Edge::door); 1 open, 0 closed
  static constexpr std::string_view kEdgeBlocked = "edge_blocked";      // where: an edge id; 1 blocked, 0 passable
  static constexpr std::string_view kPersonPresent = "person_present";  // where: a node; 1 someone there, 0 nobody

  std::string what;   // the kind, e.g. "door_open", "person_present"
  std::string where;  // a node, edge or door id
  Time when{};
  double value = 0;   // 1/0 for binary observations, a measurement otherwise
  std::string text{};  // anything else worth keeping, for people; may be empty
  std::string source{};  // who saw it when not the robot: a building sensor's name; empty: the robot
};

// A robot-level error or a lost connection, until on_ready().
struct RobotFault {
  enum class Kind { kError, kConnectionLost };
  Kind kind = Kind::kError;
  std::string message;  // the robot's own words
};
const char* to_string(RobotFault::Kind kind);

// The actions a robot says it can run, and who says so (for people: "vehicle acme/agv-7 (its
// factsheet)").
struct ActionSupport {
  std::string robot;
  std::vector<std::string> actions;  // action names, as Action::name
};

// What the robot tells the executor. Called on the executor's clock thread.
class RobotListener {
 public:
  virtual ~RobotListener() = default;
  virtual void on_edge_finished(const EdgeAttempt& attempt) = 0;
  virtual void on_action_finished(const ActionResult& result) = 0;
  // The running action says whether it may be interrupted now (e.g. not while talking to a
  // person). The executor reads the latest value before every preemption.
  virtual void on_interruptible_changed(bool interruptible) = 0;
  virtual void on_observation(const Observation& observation) = 0;
  virtual void on_fault(const RobotFault& fault) = 0;
  virtual void on_ready() = 0;  // the fault is over
};

class Robot {
 public:
  virtual ~Robot() = default;
  virtual void set_listener(RobotListener* listener) = 0;
  // Lifecycle: activate() before the first command (connects, claims the vehicle); deactivate()
  // stops what runs and releases it. A robot that is not ready after activate() reports a fault.
  virtual Status activate() = 0;
  virtual void deactivate() = 0;

  // The node the robot is at; while driving, the last node it passed; off the nodes, the last
  // node it was known to be at.
  virtual map::NodeIndex location() const = 0;
  // The metric pose, for robots that report one.
  virtual std::optional<map::Pose> position() const = 0;
  // True from drive()/run_action() until its last callback has been delivered (see above).
  virtual bool busy() const = 0;
  // Precondition: !busy() and a route as Route says, whose first edge leaves location().
  virtual void drive(const Route& route) = 0;
  // Runs one action of a task where the robot is. `expected` is its planned duration, which a
  // simulated robot uses as the mean of its own. Precondition: !busy().
  virtual void run_action(const Action& action, Duration expected) = 0;
  // Stops whatever runs; its callback reports it cancelled. Does nothing when idle.
  virtual void cancel() = 0;
  // State of charge in [0, 1].
  virtual double battery() const = 0;
  // True while the robot is on its charger (at the dock and not moving).
  virtual bool charging() const = 0;
  // The current fault, if any.
  virtual std::optional<RobotFault> fault() const = 0;
  // The actions the robot can run, when it says (a VDA 5050 vehicle's factsheet lists them); the
  // executor refuses a task with any other action when it is submitted. Nothing: it does not say,
  // and every action is tried (one it cannot run fails at its place).
  virtual std::optional<ActionSupport> supported_actions() const { return std::nullopt; }

  // One edge, committed.
  void traverse(map::EdgeIndex edge) { drive(Route{.edges = {edge}, .committed = 1}); }
};

// Why the robot cannot run `actions`, for people ("vehicle acme/agv-7 (its factsheet) cannot run
// the action 'check'; it runs: noop, pick, drop"), naming the first it cannot run; nothing when it
// can run them all or does not say which it can.
std::optional<std::string> cannot_run(const Robot& robot, const std::vector<Action>& actions);

}  // namespace rondo::exec
