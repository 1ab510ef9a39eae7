// Instants and durations. `Time` is a UTC instant with millisecond resolution and `Duration` a
// span of milliseconds; every module uses these two and nothing else for time.
//
//   Time t = *parse_time("2014-09-02T16:24:00Z");
//   Time later = t + minutes(5);
//   std::cout << format_time(later);           // 2014-09-02T16:29:00Z
//   double s = to_seconds(later - t);          // 300.0
//
// Local time of day and day of week need a time zone: see timezone.h.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <string_view>

#include "rondo/core/result.h"

namespace rondo {

using Duration = std::chrono::milliseconds;
using Time = std::chrono::sys_time<Duration>;

using std::chrono::hours;
using std::chrono::milliseconds;
using std::chrono::minutes;

inline constexpr Duration seconds(std::int64_t s) { return std::chrono::seconds(s); }

// Conversions to and from floating-point seconds, rounded to the nearest millisecond.
// from_seconds clamps to +-kMaxSeconds and maps NaN to zero: use it on computed values only.
// Input goes through checked_from_seconds, which refuses NaN, infinities and anything whose
// milliseconds would not fit ("... seconds is out of range").
inline constexpr double kMaxSeconds = 9.0e12;  // about 285,000 years; ms fit in int64 with room
Duration from_seconds(double s);
Result<Duration> checked_from_seconds(double s);
double to_seconds(Duration d);
Time from_unix_seconds(double s);
double to_unix_seconds(Time t);

// ISO 8601 with an explicit zone: "2014-09-02T16:24:00Z", "2014-09-02T17:24:00.250+01:00".
// A time without a zone is an error here; TimeZone::parse_time reads local times.
Result<Time> parse_time(std::string_view text);
// The UTC form, with milliseconds only when they are not zero.
std::string format_time(Time t);

// Durations as people write them: "90" or "90s" (seconds), "2.5m", "1h30m", "1h 5m 3s", "250ms",
// or clock form "01:30:00" / "05:00" (hours:minutes[:seconds]). Negative durations are rejected.
Result<Duration> parse_duration(std::string_view text);

// "hh:mm" or "hh:mm:ss" as a time since midnight; "24:00" is allowed as the end of a day.
Result<Duration> parse_time_of_day(std::string_view text);
// The shortest exact form: "1h30m", "45s", "1.5s", "0s".
std::string format_duration(Duration d);
// A time since midnight as a clock reading: "08:45", "24:00", "09:00:30".
std::string format_time_of_day(Duration since_midnight);

}  // namespace rondo
