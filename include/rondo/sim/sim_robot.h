// The simulated robot: implements exec::Robot on a Clock (a SimClock for weeks of life in
// seconds) with edges from an EdgeWorld, actions from an ActionModel and a BatteryModel.
//
//   exec::SimClock clock(start);
//   auto world = load_world("examples/g4s/world.yaml", map, zone);
//   SimRobot robot(clock, map, *world, {.start = dock, .dock = dock, .seed = 7});
//   robot.set_listener(&executor);
//   robot.traverse(edge);          // on_edge_finished arrives later, from the clock
//   clock.run_until(start + days(7));
//
// Contract (exec/robot.h, all kept): exactly one callback per committed edge and per
// run_action(), always posted on the clock, never from inside the call — also after cancel(),
// which delivers the cancelled result at clock.now() and forgets the pending finish. busy() stays
// true until the last callback is delivered (it is false inside the callback, so the listener may
// start the next thing). The robot drives a route's committed edges one after the other and
// ignores its horizon. A failed or cancelled edge leaves the robot where it started and ends the
// drive. An action with a non-interruptible span posts on_interruptible_changed(false) at its
// start and (true) when the span ends, or before the cancelled result when cancelled during the
// span.
// Door sensor (SimWorld::door_sensor): after every edge attempt, before its callback, the robot
// reports an observation "door_open" (1 open, 0 closed) of each door within range that it does
// not miss, from a random stream of its own (so the run's other draws are the same with or without
// it).
// Faults, for tests and demonstrations: inject_fault() ends a running edge or action with the
// outcome kRobotFault and reports the fault; clear_fault() reports the robot ready. While in fault,
// drive() and run_action() end at once with kRobotFault.
// Several SimRobots may share one world (a fleet in one building): its doors and spells are the
// same for all; each has its own random stream, battery and speed (SimRobotOptions). Without a
// Traffic they pass through each other; with one (SimRobotOptions::traffic, shared by all of them)
// a robot asks it before each edge, and when its way is taken it is held up: it waits at its node,
// looks again when the traffic says its way may have cleared, and after the traffic's hold_timeout
// the attempt fails with the blocker's name ("held up by r2 at WayPoint7"). The held time is part
// of the attempt's duration; a held robot drains its battery as moving (its navigation is on).
// Figures: distance_m() counts the length of successfully crossed edges only (a failed or
// cancelled attempt ends where it began and counts 0 m). charging_time() is the time spent idle
// at the dock. The battery drains by the hour in each mode (BatteryModel) and, at the end of each
// successfully crossed edge, by BatteryModel::per_metre for its map length. An empty battery fails
// every edge and run_action() at once (duration 0); with BatteryModel::rescue_after, a robot that
// has stood empty away from its dock that long is carried back onto the dock at its next command
// (which fails, and leaves it there).
// Misuse (drive() while busy, a route that does not leave location() or is not consecutive)
// throws std::logic_error.
// The clock, map and world must outlive the robot; the destructor cancels its pending events.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rondo/exec/clock.h"
#include "rondo/exec/robot.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/rng.h"
#include "rondo/sim/sim_world.h"
#include "rondo/sim/traffic.h"

namespace rondo::sim {

struct SimRobotOptions {
  map::NodeIndex start = 0;
  map::NodeIndex dock = 0;
  std::uint64_t seed = 1;
  // One robot of a fleet in a shared world: its own battery (nothing: the world's), a factor on
  // every edge's time drawn from the world (0.5: half as fast), and the actions it runs (nothing:
  // it does not say; supported_actions() names it `name`).
  std::optional<BatteryModel> battery{};
  double speed = 1.0;
  std::optional<std::vector<std::string>> actions{};
  std::string name = "robot";
  // The building's traffic, shared by its robots (traffic.h); nothing: the robot is alone. Must
  // outlive the robot.
  Traffic* traffic = nullptr;
};

class SimRobot final : public exec::Robot, private TrafficListener {
 public:
  SimRobot(exec::Clock& clock, const map::TopoMap& map, SimWorld& world, SimRobotOptions options);
  ~SimRobot() override;
  SimRobot(const SimRobot&) = delete;
  SimRobot& operator=(const SimRobot&) = delete;

  void set_listener(exec::RobotListener* listener) override { listener_ = listener; }
  Status activate() override { return {}; }  // a simulated robot is always there
  void deactivate() override { cancel(); }
  map::NodeIndex location() const override { return location_; }
  std::optional<map::Pose> position() const override { return map_.node(location_).pose; }
  bool busy() const override { return job_.has_value(); }
  void drive(const exec::Route& route) override;
  void run_action(const Action& action, Duration expected) override;
  void cancel() override;
  double battery() const override;
  bool charging() const override;
  std::optional<exec::RobotFault> fault() const override { return fault_; }
  std::optional<exec::ActionSupport> supported_actions() const override;

  void inject_fault(exec::RobotFault fault);
  void clear_fault();

  double distance_m() const { return distance_m_; }
  Duration charging_time() const;
  int rescues() const { return rescues_; }  // times it was carried back onto the dock, empty

 private:
  enum class End { kNatural, kCancelled, kFault };
  // What the robot is doing: one edge attempt or one action, from drive()/run_action() until
  // its callback is delivered.
  struct Job {
    bool is_edge = true;
    map::EdgeIndex edge = 0;
    std::string action{};
    Time start{};
    bool success = true;
    Duration duration{0};
    std::uint64_t finish_post = 0;
    std::uint64_t interruptible_post = 0;  // 0 when no end of a non-interruptible span is pending
    End end = End::kNatural;
    std::string message{};  // why it failed
    // With a traffic: waiting at the start node to enter the edge (held), or on it (entered).
    bool held = false;
    bool entered = false;
    std::uint64_t hold_timeout_post = 0;
    std::uint64_t recheck_post = 0;
  };

  // Schedules `callback` on the clock and remembers it until it runs, so that it can be cancelled
  // and the destructor can forget it. Returns a key (> 0) for unpost().
  std::uint64_t post(Time at, std::function<void()> callback);
  void unpost(std::uint64_t key);
  void start(Job job);
  void start_edge(map::EdgeIndex edge);
  // Draws the edge from the world at now() (after any hold: the held time comes first).
  void sample_edge(Job& job);
  // The traffic's part of an edge: enter at once, or wait (traffic.h).
  void hold(Job job);
  void on_way_may_be_clear() override;
  void look_again();                            // the way may have cleared: enter, or keep waiting
  void give_up_hold();                          // hold_timeout: the attempt fails, naming the blocker
  void leave_hold(HoldUp::End how);             // the hold ends: passed, timed out, stopped (cancel, fault)
  void stop_job(End end, std::string message);  // cancel() and inject_fault()

  const BatteryModel& battery_model() const { return options_.battery ? *options_.battery : world_.battery; }
  BatteryModel::Mode mode() const;
  void settle_battery();  // accounts the time since the last change, before the mode changes
  // Empty away from the dock for BatteryModel::rescue_after: carried back onto the dock.
  void rescue_if_stranded();
  void finish();          // the job's end: update state, then deliver the callback
  void deliver(const Job& job);
  void notify_interruptible(bool interruptible);
  void sense_doors();

  exec::Clock& clock_;
  const map::TopoMap& map_;
  SimWorld& world_;
  SimRobotOptions options_;
  Rng rng_;
  Rng sensor_rng_;
  exec::RobotListener* listener_ = nullptr;
  map::NodeIndex location_;
  std::optional<Job> job_;
  std::vector<map::EdgeIndex> route_;  // committed edges still to drive after the current one
  std::optional<exec::RobotFault> fault_;
  std::vector<std::vector<std::pair<std::string, map::EdgeIndex>>> doors_near_;  // per node: door, one edge
  double battery_;
  Time battery_since_;
  std::optional<Time> empty_since_;  // empty and away from the dock since, at a command
  int rescues_ = 0;
  Duration charging_time_{0};
  double distance_m_ = 0;
  std::map<std::uint64_t, exec::TimerId> posted_;
  Traffic::RobotId traffic_id_ = 0;  // with options_.traffic
  std::uint64_t next_post_ = 1;
};

}  // namespace rondo::sim
