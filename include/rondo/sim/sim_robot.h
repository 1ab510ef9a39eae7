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
// Contract (exec/robot.h, all kept): exactly one callback per traverse()/run_action(), always
// posted on the clock, never from inside the call — also after cancel(), which delivers the
// cancelled result at clock.now() and forgets the pending finish. busy() stays true until that
// callback is delivered (it is false inside the callback, so the listener may start the next
// thing). A failed or cancelled edge leaves the robot where it started. An action with a
// non-interruptible span posts on_interruptible_changed(false) at its start and (true) when the
// span ends, or before the cancelled result when cancelled during the span.
// Figures: distance_m() counts the length of successfully crossed edges only (a failed or
// cancelled attempt ends where it began and counts 0 m). charging_time() is the time spent idle
// at the dock. An empty battery fails every traverse() and run_action() at once (duration 0).
// Misuse (traverse() while busy, an edge that does not leave location()) throws std::logic_error.
// The clock, map and world must outlive the robot; the destructor cancels its pending events.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>

#include "rondo/exec/clock.h"
#include "rondo/exec/robot.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/rng.h"
#include "rondo/sim/sim_world.h"

namespace rondo::sim {

struct SimRobotOptions {
  map::NodeIndex start = 0;
  map::NodeIndex dock = 0;
  std::uint64_t seed = 1;
};

class SimRobot final : public exec::Robot {
 public:
  SimRobot(exec::Clock& clock, const map::TopoMap& map, SimWorld& world, SimRobotOptions options);
  ~SimRobot() override;
  SimRobot(const SimRobot&) = delete;
  SimRobot& operator=(const SimRobot&) = delete;

  void set_listener(exec::RobotListener* listener) override { listener_ = listener; }
  map::NodeIndex location() const override { return location_; }
  bool busy() const override { return job_.has_value(); }
  void traverse(map::EdgeIndex edge) override;
  void run_action(const Action& action, Duration expected) override;
  void cancel() override;
  double battery() const override;
  bool charging() const override;

  double distance_m() const { return distance_m_; }
  Duration charging_time() const;

 private:
  // What the robot is doing: one edge attempt or one action, from traverse()/run_action() until
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
    bool cancelled = false;
    std::string message{};  // why an action failed
  };

  // Schedules `callback` on the clock and remembers it until it runs, so that it can be cancelled
  // and the destructor can forget it. Returns a key (> 0) for unpost().
  std::uint64_t post(Time at, std::function<void()> callback);
  void unpost(std::uint64_t key);
  void start(Job job);

  BatteryModel::Mode mode() const;
  void settle_battery();  // accounts the time since the last change, before the mode changes
  void finish();          // the job's end: update state, then deliver the callback
  void deliver(const Job& job);
  void notify_interruptible(bool interruptible);

  exec::Clock& clock_;
  const map::TopoMap& map_;
  SimWorld& world_;
  SimRobotOptions options_;
  Rng rng_;
  exec::RobotListener* listener_ = nullptr;
  map::NodeIndex location_;
  std::optional<Job> job_;
  double battery_;
  Time battery_since_;
  Duration charging_time_{0};
  double distance_m_ = 0;
  std::map<std::uint64_t, exec::TimerId> posted_;
  std::uint64_t next_post_ = 1;
};

}  // namespace rondo::sim
