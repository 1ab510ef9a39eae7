// The executor's view of the battery (docs/executor.md, "Battery"): a reading of
// Robot::battery() at every robot callback and just before every command, what the robot did
// between two readings (metres crossed, hours moving, acting, idle, on the charger), each such
// interval fed to the BatteryEstimator, and the run's figures (the lowest reading, the stays on
// the charger). Because the readings bracket every command, each interval is one kind of thing:
// a command, or a stay where the robot stood (on the charger or not).
//
//   BatteryWatch watch(map);
//   watch.read(clock.now(), robot.battery(), robot.charging());   // before drive()
//   watch.edge_finished(attempt);                                  // in on_edge_finished
//   watch.read(clock.now(), robot.battery(), robot.charging());
//   watch.estimator().predict({.metres = 120, .hours_moving = 0.1});
#pragma once

#include <optional>

#include "rondo/core/time.h"
#include "rondo/exec/battery_estimator.h"
#include "rondo/exec/executor_types.h"
#include "rondo/exec/robot.h"
#include "rondo/map/topo_map.h"

namespace rondo::exec {

class BatteryWatch {
 public:
  explicit BatteryWatch(const map::TopoMap& map, const BatteryPrior& prior = {}) : map_(map), estimator_(prior) {}

  // A reading at `now`: closes the interval since the previous one (its time not spent on the
  // edges and actions reported meanwhile was spent standing, on the charger when the previous
  // reading said so) and learns from it.
  void read(Time now, double level, bool charging);
  // What the robot did since the last reading: an edge attempt (its time; its length when it
  // was crossed), an action (its time).
  void edge_finished(const EdgeAttempt& attempt);
  void action_finished(const ActionResult& result);

  // The last reading (1 before the first).
  double level() const { return last_ ? last_->level : 1.0; }
  const BatteryEstimator& estimator() const { return estimator_; }
  // Goes on from what an estimator learned before (a restart); false when `state` is not one.
  bool restore_estimator(const BatteryEstimator::State& state) { return estimator_.restore(state); }
  // The figures so far (BatteryFigures::low_battery is the executor's to fill in).
  BatteryFigures figures() const;

 private:
  struct Reading {
    Time at{};
    double level = 1;
    bool charging = false;
  };

  const map::TopoMap& map_;
  BatteryEstimator estimator_;
  std::optional<Reading> last_;
  BatteryUse since_{};  // the edges and actions since the last reading
  Duration busy_{0};    //   and their time
  std::size_t readings_ = 0;
  std::size_t empty_readings_ = 0;
  double lowest_ = 1;
  std::optional<Time> lowest_at_;
  int charges_ = 0;
  Duration on_charger_{0};
};

}  // namespace rondo::exec
