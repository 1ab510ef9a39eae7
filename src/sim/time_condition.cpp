#include "rondo/sim/time_condition.h"

#include <algorithm>

namespace rondo::sim {

bool TimeCondition::matches(const TimeZone& zone, Time t) const {
  if (!days.empty() && std::find(days.begin(), days.end(), zone.day_of_week(t)) == days.end()) return false;
  if (!dates.empty() && std::find(dates.begin(), dates.end(), zone.local_date(t)) == dates.end()) return false;
  if (!from && !to) return true;
  const Duration tod = zone.time_of_day(t);
  const Duration begin = from.value_or(Duration{0});
  const Duration end = to.value_or(hours(24));
  if (begin <= end) return tod >= begin && tod < end;
  return tod >= begin || tod < end;  // wraps past midnight
}

std::vector<std::chrono::weekday> weekdays() {
  return {std::chrono::Monday, std::chrono::Tuesday, std::chrono::Wednesday, std::chrono::Thursday,
          std::chrono::Friday};
}

std::vector<std::chrono::weekday> weekend_days() { return {std::chrono::Saturday, std::chrono::Sunday}; }

bool any_matches(const std::vector<TimeCondition>& conditions, const TimeZone& zone, Time t) {
  return std::any_of(conditions.begin(), conditions.end(), [&](const TimeCondition& c) { return c.matches(zone, t); });
}

}  // namespace rondo::sim
