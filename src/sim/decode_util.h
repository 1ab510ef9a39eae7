// Small decoders shared by the world and request files: bounded numbers, durations, days of the
// week, dates, local time spans and actions, each failing with the field's file:line and path.
#pragma once

#include <chrono>
#include <string_view>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"
#include "rondo/sim/time_condition.h"

namespace rondo::sim::detail {

// A number in [low, high].
Result<double> number_in(const Field& f, double low, double high);
// Sets `out` from the optional member `key` when present.
Status read_number(const Field& parent, std::string_view key, double low, double high, double& out);
Status read_duration(const Field& parent, std::string_view key, Duration& out);
// A local time of day such as "12:30" (or seconds), from 00:00 to 24:00.
Result<Duration> time_of_day(const Field& f);
// "weekdays", "weekends", "daily", or a list of day names (mon, tuesday...).
Result<std::vector<std::chrono::weekday>> days(const Field& f);
// {days, from, to, dates}: see TimeCondition.
Result<TimeCondition> time_condition(const Field& f, const TimeZone& zone);
// A list of time conditions.
Result<std::vector<TimeCondition>> time_conditions(const Field& f, const TimeZone& zone);
// An action: a name, or {name, args: {key: scalar}}.
Result<Action> action(const Field& f);

}  // namespace rondo::sim::detail
