#include "rondo/core/timezone.h"

#include <gtest/gtest.h>

namespace rondo {
namespace {

using std::chrono::year;

TimeZone london() {
  auto tz = TimeZone::named("Europe/London");
  EXPECT_TRUE(tz.ok());
  return *tz;
}

TEST(TimeZone, UnknownZoneIsNotFound) {
  auto tz = TimeZone::named("Mars/Olympus_Mons");
  ASSERT_FALSE(tz.ok());
  EXPECT_EQ(tz.error().code, ErrorCode::kNotFound);
  EXPECT_NE(tz.error().message.find("Mars/Olympus_Mons"), std::string::npos);
}

TEST(TimeZone, NineOClockIsNineOClockAllYear) {
  const TimeZone tz = london();
  const Time winter = tz.at(year{2026} / 1 / 15, hours(9));
  const Time summer = tz.at(year{2026} / 7 / 15, hours(9));
  EXPECT_EQ(format_time(winter), "2026-01-15T09:00:00Z");
  EXPECT_EQ(format_time(summer), "2026-07-15T08:00:00Z");
  EXPECT_EQ(tz.time_of_day(winter), hours(9));
  EXPECT_EQ(tz.time_of_day(summer), hours(9));
  EXPECT_EQ(tz.format_local(summer), "2026-07-15T09:00:00+01:00");
}

TEST(TimeZone, DaylightSavingTransitions) {
  const TimeZone tz = london();
  // 2026-03-29: clocks go from 01:00 to 02:00. 01:30 does not exist: read with the old offset.
  EXPECT_EQ(format_time(tz.at(year{2026} / 3 / 29, minutes(90))), "2026-03-29T01:30:00Z");
  EXPECT_EQ(format_time(tz.at(year{2026} / 3 / 29, hours(3))), "2026-03-29T02:00:00Z");
  // 2026-10-25: 01:30 happens twice; the first (BST) reading is chosen.
  EXPECT_EQ(format_time(tz.at(year{2026} / 10 / 25, minutes(90))), "2026-10-25T00:30:00Z");
  // The day of the change has 23 hours.
  EXPECT_EQ(tz.at(year{2026} / 3 / 30, Duration{0}) - tz.at(year{2026} / 3 / 29, Duration{0}), hours(23));
}

TEST(TimeZone, DayOfWeekAndTimeOfWeekAreLocal) {
  const TimeZone tz = london();
  // Sunday 2026-07-19 23:30 UTC is Monday 00:30 in London.
  const Time t = *parse_time("2026-07-19T23:30:00Z");
  EXPECT_EQ(tz.day_of_week(t), std::chrono::Monday);
  EXPECT_EQ(tz.time_of_week(t), minutes(30));
  EXPECT_EQ(tz.local_date(t), year{2026} / 7 / 20);
  EXPECT_EQ(TimeZone::utc().day_of_week(t), std::chrono::Sunday);
}

TEST(TimeZone, ParsesLocalTimes) {
  const TimeZone tz = london();
  EXPECT_EQ(format_time(*tz.parse_time("2026-07-15T09:00")), "2026-07-15T08:00:00Z");
  EXPECT_EQ(format_time(*tz.parse_time("2026-07-15T09:00Z")), "2026-07-15T09:00:00Z");
  EXPECT_FALSE(tz.parse_time("2026-07-15T9:00").ok());
}

}  // namespace
}  // namespace rondo
