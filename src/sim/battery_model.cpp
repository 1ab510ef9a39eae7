#include "rondo/sim/battery_model.h"

#include <algorithm>

namespace rondo::sim {

double BatteryModel::after(double level, Mode mode, Duration elapsed) const {
  double rate = 0;  // change per hour
  switch (mode) {
    case Mode::kIdle: rate = -idle_per_hour; break;
    case Mode::kMoving: rate = -moving_per_hour; break;
    case Mode::kActing: rate = -acting_per_hour; break;
    case Mode::kCharging: rate = charging_per_hour; break;
  }
  return std::clamp(level + rate * to_seconds(elapsed) / 3600.0, 0.0, 1.0);
}

double BatteryModel::after_distance(double level, double metres) const {
  return std::clamp(level - per_metre * metres, 0.0, 1.0);
}

}  // namespace rondo::sim
