// The robot as the executor sees it (DESIGN.md, Robot interface). The simulator (sim::SimRobot)
// and every real adapter implement it; the executor cannot tell them apart.
//
//   robot.set_listener(&executor);
//   robot.traverse(edge);                  // later: listener->on_edge_finished({edge, ...})
//   robot.run_action(action, minutes(2));  // later: listener->on_action_finished({...})
//   robot.cancel();                        // the running edge or action ends as cancelled
//
// Contract:
// - One thing at a time: traverse() and run_action() are only called when !busy().
// - Every traverse() and run_action() is answered by exactly one callback, never from inside the
//   call itself (the robot posts it to the executor's clock or thread), also after cancel().
// - A failed or cancelled edge leaves the robot at the edge's start node (MISSION.md §4: the only
//   failure outcome is "stay where you are"); a successful one at its end node.
// - Times are the executor's clock: the robot reads the same Clock.
#pragma once

#include <string>

#include "rondo/core/task.h"
#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"

namespace rondo::exec {

// One attempt to cross one edge: the experience the models learn from.
struct EdgeAttempt {
  map::EdgeIndex edge = 0;
  Time start{};
  Duration duration{0};
  bool success = false;
  bool cancelled = false;  // ended by cancel(); success is then false
};

enum class ActionOutcome { kSucceeded, kFailed, kCancelled };
const char* to_string(ActionOutcome outcome);

struct ActionResult {
  std::string name{};  // the action's name, as given to run_action()
  Time start{};
  Duration duration{0};
  ActionOutcome outcome = ActionOutcome::kSucceeded;
  std::string message{};  // why it failed, for the event log; may be empty
};

// What the robot tells the executor. Called on the executor's clock/thread.
class RobotListener {
 public:
  virtual ~RobotListener() = default;
  virtual void on_edge_finished(const EdgeAttempt& attempt) = 0;
  virtual void on_action_finished(const ActionResult& result) = 0;
  // The running action says whether it may be interrupted now (e.g. not while talking to a
  // person). The executor reads the latest value before every preemption.
  virtual void on_interruptible_changed(bool interruptible) = 0;
};

class Robot {
 public:
  virtual ~Robot() = default;
  virtual void set_listener(RobotListener* listener) = 0;
  // The node the robot is at; while crossing an edge, the node it left.
  virtual map::NodeIndex location() const = 0;
  // True from traverse()/run_action() until its callback has been delivered.
  virtual bool busy() const = 0;
  // Tries to cross `edge`, which leaves location(). Precondition: !busy().
  virtual void traverse(map::EdgeIndex edge) = 0;
  // Runs one action of a task where the robot is. `expected` is its planned duration, which a
  // simulated robot uses as the mean of its own. Precondition: !busy().
  virtual void run_action(const Action& action, Duration expected) = 0;
  // Stops whatever runs; its callback reports it cancelled. Does nothing when idle.
  virtual void cancel() = 0;
  // State of charge in [0, 1].
  virtual double battery() const = 0;
  // True while the robot is on its charger (at the dock and not moving).
  virtual bool charging() const = 0;
};

}  // namespace rondo::exec
