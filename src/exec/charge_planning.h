// Planned charging (docs/executor.md, "Planned charging"): the state of charge predicted along a
// schedule from the learned battery costs, and charges inserted where they cost least when it
// would fall below the reserve.
//
// A schedule is accepted when the predicted level stays at or above the reserve plus a margin of
// `margin` standard errors of the predicted drop, at every point: the end of every task, the
// arrival at the dock before a charge, and the way home after the last task. Otherwise a charge
// pseudo-task at the dock is added to the problem, ordered before the first task that falls short
// (a precedence), with the highest priority, and the problem is solved again: the scheduler puts
// the charge where the sum of end times grows least, and what no longer fits beside it is dropped
// lowest priority first. This is repeated (a second charge for a later shortfall) up to
// `max_charges` times; what still falls short then is refused: the tasks from the first
// shortfall on are dropped for the battery.
//
//   ChargePlan plan{.estimator = watch.estimator(), .level = 0.7, .reserve = 0.2, .dock = 0, ...};
//   PlannedAnswer a = plan_charges(request, plan, [&](TryScheduleRequest& r) { return solve(r); });
//   for (const ScheduledTask& e : a.result.schedule.entries) if (e.task >= a.first_charge) ...
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/exec/battery_estimator.h"
#include "rondo/schedule/try_schedule.h"

namespace rondo::exec {

struct ChargePlan {
  BatteryEstimator estimator{};  // a copy, as learned when the problem was built
  double level = 1;              // predicted state of charge at the problem's robot.time
  double reserve = 0.2;
  double margin = 2;             // standard errors of the predicted drop kept above the reserve
  // What plans have missed so far (PlanDrift): the robot drained this much more per hour than
  // its plans said (on-demand work, overruns, retries), with this variance per hour.
  double drift_per_hour = 0;
  double drift_variance_per_hour = 0;
  schedule::LocationIndex dock = 0;
  std::vector<double> metres{};  // locations × locations, row-major: shortest distances
  Duration dock_when_waiting_over = minutes(15);  // longer waits are spent on the charger
  int max_charges = 3;

  double metres_between(schedule::LocationIndex from, schedule::LocationIndex to) const;
};

// The predicted state of charge along a schedule. Tasks with an index from `first_charge` on are
// charges: the robot stands on the charger for their duration.
struct LevelProfile {
  std::vector<double> after;  // the level at the end of each entry
  double lowest = 1;          // the lowest level at any point checked
  // The first point below reserve + margin: the position of the entry at whose arrival (a
  // charge) or end (a task) it happens, or entries.size() for the way home after the last.
  std::optional<std::size_t> short_at{};
  double short_level = 0;  // the level predicted there
  double short_floor = 0;  // reserve + margin there
  Time short_time{};
  double deficit = 0;  // the largest (reserve + margin − level) from the first shortfall on
  std::vector<std::pair<Time, double>> points{};  // every point checked: when, and the level
};
LevelProfile predict_levels(const schedule::Problem& problem, const schedule::Schedule& schedule,
                            const ChargePlan& plan, std::size_t first_charge);

// What the battery's plans missed (the margin's learned part): at each reschedule the level read
// is compared with what the last plan predicted for that moment. The error e over the h hours
// since that plan is modelled as drift·h plus noise of variance s²·h (a random walk: unplanned
// on-demand work, overruns, retries), and drift and s² are estimated with a weak prior (no drift,
// s = 0.05 per √h, worth two observations). Observations closer than 5 minutes to their plan's
// start, or past its last point, are not used.
class PlanDrift {
 public:
  void planned(std::vector<std::pair<Time, double>> points) { plan_ = std::move(points); }
  void observe(Time now, double level);
  double per_hour() const;           // clipped at zero: plans are not trusted to be pessimistic
  double variance_per_hour() const;
  std::size_t observations() const { return n_; }

 private:
  std::vector<std::pair<Time, double>> plan_;
  std::size_t n_ = 0;
  double hours_ = 0;         // Σ h
  double error_ = 0;         // Σ e
  double error_sq_ = 0;      // Σ e² / h
};

struct PlannedAnswer {
  // Its schedule holds the charges, as tasks from first_charge on (among the entries, or dropped).
  schedule::TryScheduleResult result;
  std::size_t first_charge = 0;        // the problem's task count before any charge was added
  std::vector<double> levels{};        // the level predicted at the end of each entry
  std::vector<std::pair<Time, double>> points{};  // the level predicted along the schedule
  // Dropped tasks the battery dropped: beside a charge, or refused. Their reasons say so.
  std::vector<std::size_t> for_battery{};
  bool refused = false;  // even with charges, the schedule fell short: its tail was dropped
};

// Solves `request` with `solve`, and again with charges while the schedule falls short. No
// `plan`: one call to `solve`, nothing added.
PlannedAnswer plan_charges(schedule::TryScheduleRequest& request, const ChargePlan* plan,
                           const std::function<schedule::TryScheduleResult(schedule::TryScheduleRequest&)>& solve);

}  // namespace rondo::exec
