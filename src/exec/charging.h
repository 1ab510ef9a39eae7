// What the executor keeps about the battery between its decisions (docs/executor.md, "Battery",
// "Planned charging"): the readings (BatteryWatch), the hard threshold and the resume level, a
// planned charge under way, the way to the charger found closed, what the plans missed so far
// (PlanDrift), and the levels a task or the way home must leave. It notes its own robot events
// (`battery low`, `charging`, `charged`, `charge missed`, `way home closed`) in the task book; what
// follows from them (a reschedule, a trip to the dock, a preemption) is the executor's.
//
//   Charging charging({map, options, clock, robot, book, zone, travel, snapshot});
//   charging.read();                                   // at every robot callback and before commands
//   if (!charging.low() && charging.below_threshold()) charging.enter_low();
//   if (auto s = charging.short_for(task, here)) ...;  // the task waits for a charge to s->needed
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "battery_watch.h"
#include "charge_planning.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor_types.h"
#include "rondo/exec/map_travel.h"
#include "rondo/exec/robot.h"
#include "rondo/exec/task_book.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/edge_model_view.h"

namespace rondo::exec {

// A state of charge for people: "14.9 %".
std::string percent(double level);

// What the executor lends its battery keeper; all of it outlives the keeper.
struct ChargingContext {
  const map::TopoMap& map;
  const ExecutorOptions& options;
  Clock& clock;
  const Robot& robot;
  TaskBook& book;
  const TimeZone& zone;
  const TravelCache& travel;            // the executor's travel estimates
  const plan::EdgeModelView& snapshot;  // the nightly snapshot read offline (no memory of failures)
};

class Charging {
 public:
  explicit Charging(ChargingContext ctx);

  // A reading of the robot's battery now (BatteryWatch::read).
  void read();
  BatteryWatch& watch() { return watch_; }
  double level() const { return watch_.level(); }
  const BatteryEstimator& estimator() const { return watch_.estimator(); }
  bool restore_estimator(const BatteryEstimator::State& state) { return watch_.restore_estimator(state); }
  PlanDrift& drift() { return drift_; }
  // The figures so far, with the times the battery fell below the hard threshold.
  BatteryFigures figures() const;

  // The level the robot charges back to after falling below the hard threshold.
  double resume_level() const;
  // By the last reading: below the hard threshold, or (charging planned) below home_level().
  bool below_threshold() const;
  // Planned charging: the reserve, plus what the way to the dock from here is predicted to take,
  // plus one more edge away from it, plus the margin; 0 when charging is not planned.
  double home_level() const;
  // The margin the plans keep (ChargePlan): `battery_margin` standard deviations of the
  // prediction, from the rates' standard error and what plans missed per hour over `hours`.
  double margin_over(const BatteryPrediction& p, double hours) const;
  // From the last reading to the resume level (or a planned charge's target, by its end), as learned.
  Duration time_to_charge() const;
  // The state of charge predicted when the robot is next free (at `free`), with the running task
  // `acting` until then.
  double level_when_free(Time free, bool acting) const;
  // Planned charging: the level task `id` needs when it leaves from `from` now (there, its work and
  // the way back to the charger, above the reserve and the margin), and why, when the battery has
  // less; nothing when it can.
  struct Short {
    double needed = 0;
    std::string why;
  };
  std::optional<Short> short_for(const TaskId& id, map::NodeIndex from) const;

  // The hard threshold: below it (enter_low, noted) until charged back to the resume level (resumed).
  bool low() const { return low_; }
  void enter_low();
  void resumed() { low_ = false; }
  Time low_since() const { return low_since_; }

  // A planned charge: on the charger until `until` (moved on by the time the way to it took, so
  // that it stays `length` there) or `target` (at least the resume level). Noted.
  void start_planned(Time until, Duration length, double target);
  bool planned() const { return planned_.has_value(); }
  void cancel_planned() { planned_.reset(); }
  // In the dispatcher's turn: true while the planned charge goes on; false once it reached its
  // target or its end, or the robot did not reach the charger in time (noted, and the charge is over).
  bool planned_goes_on();

  // The way to the charger failed on `edge` (charging planned): when to try again (noted).
  Time retry_way_home(map::EdgeIndex edge);
  // Clears the closed way once the robot crosses its edge or reaches the dock.
  void crossed(const EdgeAttempt& attempt);
  // No trip to the dock before this (the way home found closed).
  std::optional<Time> way_home_closed_until() const;

  // Tasks dropped for the battery are offered again at most once a slot while the robot is on the
  // charger: the next time they may be (reoffered(now) moves it on).
  Time next_reoffer() const { return reoffer_at_; }
  void reoffered(Time now) { reoffer_at_ = now + ctx_.options.slot_width; }

 private:
  double way_home_hours() const;                   // from here to the dock, now: expected, at most a day
  BatteryPrediction way_home(double hours) const;  // the same way, `hours` of it moving
  double edge_cost(map::EdgeIndex e) const;        // the battery one crossing of `e` takes, expected

  ChargingContext ctx_;
  BatteryWatch watch_;
  PlanDrift drift_;
  std::vector<double> metres_home_;  // from every node to the dock (charging planned)
  bool low_ = false;
  int low_count_ = 0;
  Time low_since_{};
  struct PlannedCharge {
    Time since;
    Time until;
    Duration length;
    double target = 1;
    bool on_charger = false;
  };
  std::optional<PlannedCharge> planned_;
  struct WayHomeClosed {
    map::EdgeIndex edge = 0;
    int failures = 0;
    Time retry_at{};
  };
  std::optional<WayHomeClosed> way_home_closed_;
  Time reoffer_at_{};
};

}  // namespace rondo::exec
