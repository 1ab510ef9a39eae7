// ISO 8601 date-time parsing shared by parse_time (UTC or offset) and TimeZone (local times).
#pragma once

#include <chrono>
#include <optional>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo::detail {

struct ParsedDateTime {
  Time local;                           // the wall-clock reading, as if it were UTC
  std::optional<Duration> utc_offset;   // "Z" is zero; absent when the text names no zone
};

// "YYYY-MM-DD", "YYYY-MM-DDThh:mm[:ss[.fff]]" with an optional "Z" or "+hh:mm"/"-hh:mm";
// a space may stand for the "T".
Result<ParsedDateTime> parse_iso_datetime(std::string_view text);

// "YYYY-MM-DD" alone.
Result<std::chrono::year_month_day> parse_iso_date(std::string_view text);

// "hh:mm" or "hh:mm:ss" as a time of day; "24:00" is allowed as the end of a day.
Result<Duration> parse_time_of_day(std::string_view text);

}  // namespace rondo::detail
