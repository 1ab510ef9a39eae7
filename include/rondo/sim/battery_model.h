// The simulated robot's battery: a state of charge in [0, 1] that drains at a constant rate
// while moving and while acting (and optionally while idle), by `per_metre` for every metre of an
// edge crossed (on top of the hourly rate while moving), and charges at a constant rate while the
// robot stands idle at its dock. Rates are fractions of a full battery per hour or per metre.
//
//   BatteryModel b{.moving_per_hour = 0.25, .charging_per_hour = 0.5, .per_metre = 0.0002};
//   double soc = b.after(0.8, BatteryModel::Mode::kMoving, minutes(30));   // 0.675
//   soc = b.after_distance(soc, 250.0);                                    // 0.625
//
// Contract: after() is clamped to [0, 1]. An empty battery stops the robot: SimRobot fails every
// traverse() and run_action() at once until it has charged (docs/simulation.md).
#pragma once

#include <optional>

#include "rondo/core/time.h"

namespace rondo::sim {

struct BatteryModel {
  enum class Mode { kIdle, kMoving, kActing, kCharging };

  double initial = 1.0;
  double moving_per_hour = 0.20;
  double acting_per_hour = 0.10;
  double idle_per_hour = 0.0;
  double charging_per_hour = 0.50;
  double per_metre = 0.0;  // for each metre of an edge crossed (SimRobot: at the edge's end)
  // A robot that stands empty away from its dock this long is carried back onto it (people find
  // it), at its next command; nothing: it stays where it ran flat.
  std::optional<Duration> rescue_after{};

  // The state of charge after `elapsed` in `mode`, starting from `level`.
  double after(double level, Mode mode, Duration elapsed) const;
  // The state of charge after driving `metres`, starting from `level` (the distance's share only).
  double after_distance(double level, double metres) const;
  bool operator==(const BatteryModel&) const = default;
};

}  // namespace rondo::sim
