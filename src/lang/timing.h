// The time words at the end of a command (docs/commands.md, "When"): "now", "today",
// "tomorrow", "on friday", "before 15:00", "after 14:00", "between 20:00 and 20:15",
// "from 08:00 to 18:00", "at 09:00", "every 2 hours", "every weekday", "daily", "on weekdays",
// "for 10 minutes", "with priority 4", "in 10 minutes", "in half an hour". Internal to rondo::lang.
#pragma once

#include <chrono>
#include <optional>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "tokens.h"

namespace rondo::lang::detail {

struct Timing {
  bool now = false;
  std::optional<int> day_offset;                       // today 0, tomorrow 1
  std::optional<std::chrono::weekday> on_weekday;      // "on friday"
  std::optional<std::chrono::year_month_day> on_date;  // "on 2026-11-24"
  std::optional<Duration> before;                      // local times of day
  std::optional<Duration> after;
  std::optional<Duration> at;
  std::optional<std::pair<Duration, Duration>> between;
  std::optional<Duration> in;                             // "in 10 minutes": that long after now
  std::optional<Duration> every;                          // "every 2 hours"
  std::optional<std::vector<std::chrono::weekday>> days;  // "every weekday", "daily", "on weekdays"
  std::optional<Duration> duration;                       // "for 10 minutes"
  std::optional<int> priority;                            // "with priority 4"

  bool recurring() const { return every.has_value() || days.has_value(); }
  bool any() const;
};

// Whether tokens[i] opens a time clause (so the words before it are the command's body).
bool starts_timing(const Tokens& tokens, std::size_t i);

// Reads every clause from tokens[from] to the end; an error names the first word it cannot read.
Result<Timing> parse_timing(const Tokens& tokens, std::size_t from);

}  // namespace rondo::lang::detail
