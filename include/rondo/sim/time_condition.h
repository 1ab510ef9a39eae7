// When a rhythm of the simulated world applies: days of the week, a span of local time of day and
// specific local dates, all in the deployment's time zone.
//
//   TimeCondition lunch{.days = weekdays(), .from = hours(12), .to = hours(13) + minutes(30)};
//   bool crowded = lunch.matches(zone, t);   // 12:00 <= local time < 13:30, Monday to Friday
//
// An empty `days` or `dates` list does not restrict. Without from/to the whole day matches; a span
// with from > to wraps past midnight (22:00-06:00). A condition with both days and dates needs both.
#pragma once

#include <chrono>
#include <optional>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/core/timezone.h"

namespace rondo::sim {

struct TimeCondition {
  std::vector<std::chrono::weekday> days{};
  std::optional<Duration> from{};  // local time of day, [0, 24h]
  std::optional<Duration> to{};
  std::vector<std::chrono::year_month_day> dates{};

  bool matches(const TimeZone& zone, Time t) const;
  bool operator==(const TimeCondition&) const = default;
};

// Monday to Friday, and Saturday and Sunday.
std::vector<std::chrono::weekday> weekdays();
std::vector<std::chrono::weekday> weekend_days();

// True when any of `conditions` matches (false for an empty list).
bool any_matches(const std::vector<TimeCondition>& conditions, const TimeZone& zone, Time t);

}  // namespace rondo::sim
