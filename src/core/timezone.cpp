#include "rondo/core/timezone.h"

#include <date/date.h>
#include <date/tz.h>
#include <fmt/format.h>

#include <exception>

#include "time_parsing.h"

namespace rondo {
namespace {

date::local_time<Duration> to_date_local(std::chrono::year_month_day day, Duration tod) {
  const std::chrono::sys_days sd{day};
  return date::local_time<Duration>{sd.time_since_epoch() + tod};
}

}  // namespace

Result<TimeZone> TimeZone::named(std::string_view name) {
  try {
    const date::time_zone* zone = date::locate_zone(std::string(name));
    return TimeZone(zone, std::string(name));
  } catch (const std::exception& e) {
    return Error::not_found("time zone '" + std::string(name) +
                            "' is not in the IANA database (is the tzdata package installed?)");
  }
}

TimeZone TimeZone::utc() {
  static const date::time_zone* zone = date::locate_zone("UTC");
  return TimeZone(zone, "UTC");
}

Duration TimeZone::utc_offset(Time t) const {
  return std::chrono::duration_cast<Duration>(zone_->get_info(t).offset);
}

std::chrono::year_month_day TimeZone::local_date(Time t) const {
  const Time local{(t + utc_offset(t)).time_since_epoch()};
  return std::chrono::year_month_day{std::chrono::floor<std::chrono::days>(local)};
}

Duration TimeZone::time_of_day(Time t) const {
  const Time local = t + utc_offset(t);
  return local - std::chrono::floor<std::chrono::days>(local);
}

std::chrono::weekday TimeZone::day_of_week(Time t) const {
  const Time local = t + utc_offset(t);
  return std::chrono::weekday{std::chrono::floor<std::chrono::days>(local)};
}

Duration TimeZone::time_of_week(Time t) const {
  const unsigned since_monday = (day_of_week(t).iso_encoding() + 6) % 7;  // Monday = 0
  return std::chrono::days(since_monday) + time_of_day(t);
}

Time TimeZone::at(std::chrono::year_month_day day, Duration time_of_day) const {
  const auto local = to_date_local(day, time_of_day);
  const auto info = zone_->get_info(local);
  // unique: the one offset. ambiguous (clocks went back): the first reading. nonexistent (clocks
  // jumped over it): the offset before the jump, which lands as far past the jump as the reading.
  return Time{local.time_since_epoch() - std::chrono::duration_cast<Duration>(info.first.offset)};
}

Result<Time> TimeZone::parse_time(std::string_view text) const {
  auto parsed = detail::parse_iso_datetime(text);
  if (!parsed) return parsed.error();
  if (parsed->utc_offset) return parsed->local - *parsed->utc_offset;
  const auto midnight = std::chrono::floor<std::chrono::days>(parsed->local);
  return at(std::chrono::year_month_day{midnight}, parsed->local - midnight);
}

std::string TimeZone::format_clock(Time t) const {
  const auto info = zone_->get_info(t);
  const Duration tod = time_of_day(t);
  const auto m = std::chrono::duration_cast<std::chrono::minutes>(tod).count();
  return fmt::format("{:02}:{:02} {}", m / 60, m % 60, info.abbrev);
}

std::string TimeZone::format_local(Time t) const {
  const Duration offset = utc_offset(t);
  std::string utc = rondo::format_time(t + offset);  // local reading, formatted with a trailing Z
  utc.pop_back();
  const auto off_min = std::chrono::duration_cast<std::chrono::minutes>(offset).count();
  const long long a = off_min < 0 ? -off_min : off_min;
  return utc + fmt::format("{}{:02}:{:02}", off_min < 0 ? '-' : '+', a / 60, a % 60);
}

}  // namespace rondo
