// The deployment's time zone: local time of day, day of week and calendar dates for UTC instants,
// and UTC instants for local wall-clock times, with daylight saving handled by the IANA database.
//
//   TimeZone london = *TimeZone::named("Europe/London");
//   Duration tod = london.time_of_day(t);                 // 09:00 local, summer or winter
//   Time nine = london.at(std::chrono::year{2026}/3/30, hours(9));
#pragma once

#include <chrono>
#include <string>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace date {
class time_zone;
}

namespace rondo {

class TimeZone {
 public:
  // An IANA zone name such as "Europe/London" or "UTC"; kNotFound when the database lacks it.
  static Result<TimeZone> named(std::string_view name);
  static TimeZone utc();

  const std::string& name() const { return name_; }

  // Local calendar date, time since local midnight, day of week, and time since local Monday
  // 00:00 of the instant t.
  std::chrono::year_month_day local_date(Time t) const;
  Duration time_of_day(Time t) const;
  std::chrono::weekday day_of_week(Time t) const;
  Duration time_of_week(Time t) const;
  // The offset of local time from UTC at t (e.g. +1h in British summer time).
  Duration utc_offset(Time t) const;

  // The instant at which local clocks on `day` read `time_of_day` (which may be 24:00 or more:
  // it counts from local midnight). A reading skipped by a spring-forward change maps to the
  // same distance past the change; a reading that happens twice maps to the first.
  Time at(std::chrono::year_month_day day, Duration time_of_day) const;

  // ISO 8601 as in parse_time(); a time without a zone is read as local time in this zone.
  Result<Time> parse_time(std::string_view text) const;
  // ISO 8601 local time with its offset, e.g. "2026-07-01T09:00:00+01:00".
  std::string format_local(Time t) const;
  // The local clock time to the minute with the zone's abbreviation, for people: "09:05 BST". The
  // one format of times in reasons and messages.
  std::string format_clock(Time t) const;

  bool operator==(const TimeZone& other) const { return name_ == other.name_; }

 private:
  TimeZone(const date::time_zone* zone, std::string name) : zone_(zone), name_(std::move(name)) {}
  const date::time_zone* zone_;  // owned by the process-wide tz database; never null
  std::string name_;
};

}  // namespace rondo
