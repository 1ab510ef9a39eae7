#include "battery_watch.h"

#include <algorithm>

#include "rondo/map/map_geometry.h"

namespace rondo::exec {

void BatteryWatch::edge_finished(const EdgeAttempt& a) {
  since_.hours_moving += to_seconds(a.duration) / 3600;
  busy_ += a.duration;
  if (a.succeeded()) since_.metres += map::edge_length(map_, a.edge);
}

void BatteryWatch::action_finished(const ActionResult& r) {
  since_.hours_acting += to_seconds(r.duration) / 3600;
  busy_ += r.duration;
}

void BatteryWatch::read(Time now, double level, bool charging) {
  level = std::clamp(level, 0.0, 1.0);
  ++readings_;
  if (level <= 1e-6) ++empty_readings_;
  if (level < lowest_ || !lowest_at_) {
    lowest_ = level;
    lowest_at_ = now;
  }
  if (last_) {
    BatteryUse use = since_;
    const Duration standing = std::max(Duration{0}, now - last_->at - busy_);
    if (last_->charging) {
      use.hours_charging = to_seconds(standing) / 3600;
      on_charger_ += standing;
    } else {
      use.hours_idle = to_seconds(standing) / 3600;
    }
    estimator_.observe(last_->level, level, use);
  }
  // A stay on the charger begins at the first reading that finds the robot on it.
  if (charging && (!last_ || !last_->charging)) ++charges_;
  last_ = Reading{.at = now, .level = level, .charging = charging};
  since_ = {};
  busy_ = Duration{0};
}

BatteryFigures BatteryWatch::figures() const {
  return {.readings = readings_,
          .lowest = lowest_,
          .lowest_at = lowest_at_,
          .charges = charges_,
          .on_charger = on_charger_,
          .low_battery = 0,
          .empty_readings = empty_readings_,
          .learned = estimator_.rates(),
          .standard_errors = estimator_.standard_errors(),
          .intervals_learned = estimator_.observations()};
}

}  // namespace rondo::exec
