#include "rondo/core/routine.h"

#include <gtest/gtest.h>

namespace rondo {
namespace {

using namespace std::chrono;

TimeZone london() { return *TimeZone::named("Europe/London"); }

Routine exit_checks() {
  Routine r;
  r.name = "exit-checks";
  r.task.activity = "check the emergency exits";
  r.task.duration = minutes(5);
  r.task.start_node = "WayPoint2";
  r.window_start = hours(8);
  r.window_end = hours(18);
  r.every = hours(2);
  r.days = {Monday, Tuesday, Wednesday, Thursday, Friday};
  r.dates_off = {year{2026} / 12 / 25};
  return r;
}

TEST(Routine, RepeatsInsideItsWindowOnWeekdays) {
  const auto tasks = instances_on(exit_checks(), year{2026} / 11 / 23, london());  // a Monday
  ASSERT_EQ(tasks.size(), 5u);
  EXPECT_EQ(tasks[0].id, "exit-checks@2026-11-23T08:00");
  EXPECT_EQ(format_time(tasks[0].window->release), "2026-11-23T08:00:00Z");
  EXPECT_EQ(format_time(tasks[0].window->deadline), "2026-11-23T10:00:00Z");
  EXPECT_EQ(tasks[4].id, "exit-checks@2026-11-23T16:00");
  EXPECT_EQ(format_time(tasks[4].window->deadline), "2026-11-23T18:00:00Z");
  for (const auto& t : tasks) EXPECT_TRUE(validate(t).ok());
}

TEST(Routine, DaysAndDatesOff) {
  const Routine r = exit_checks();
  EXPECT_TRUE(instances_on(r, year{2026} / 11 / 22, london()).empty());  // Sunday
  EXPECT_TRUE(instances_on(r, year{2026} / 12 / 25, london()).empty());  // a Friday, but a holiday
  EXPECT_FALSE(instances_on(r, year{2026} / 12 / 24, london()).empty());
  Routine bounded = r;
  bounded.first_day = year{2026} / 11 / 24;
  bounded.last_day = year{2026} / 11 / 25;
  EXPECT_FALSE(runs_on(bounded, year{2026} / 11 / 23));
  EXPECT_TRUE(runs_on(bounded, year{2026} / 11 / 25));
  EXPECT_FALSE(runs_on(bounded, year{2026} / 11 / 26));
}

TEST(Routine, LocalTimesHoldAcrossDaylightSaving) {
  Routine r = exit_checks();
  r.every.reset();
  r.window_start = hours(9);
  r.window_end = hours(12);
  r.days.clear();
  const auto summer = instances_on(r, year{2026} / 7 / 1, london());
  const auto winter = instances_on(r, year{2026} / 12 / 1, london());
  ASSERT_EQ(summer.size(), 1u);
  ASSERT_EQ(winter.size(), 1u);
  EXPECT_EQ(format_time(summer[0].window->release), "2026-07-01T08:00:00Z");
  EXPECT_EQ(format_time(winter[0].window->release), "2026-12-01T09:00:00Z");
}

TEST(Routine, ACutShortLastWindowThatCannotHoldTheTaskIsSkipped) {
  Routine r = exit_checks();
  r.every = hours(3);          // 08, 11, 14, 17 (the last one is 17:00-18:00)
  r.task.duration = minutes(90);
  const auto tasks = instances_on(r, year{2026} / 11 / 23, london());
  ASSERT_EQ(tasks.size(), 3u);
  EXPECT_EQ(tasks.back().id, "exit-checks@2026-11-23T14:00");
}

TEST(Routine, ValidationNamesTheField) {
  struct Case {
    const char* name;
    void (*spoil)(Routine&);
    const char* expect;
  };
  const Case cases[] = {
      {"no name", [](Routine& r) { r.name.clear(); }, "r.name: "},
      {"window backwards", [](Routine& r) { r.window_end = hours(7); }, "r.window.to: "},
      {"window past midnight", [](Routine& r) { r.window_end = hours(25); }, "r.window.to: must be 24:00"},
      {"zero repeat", [](Routine& r) { r.every = Duration{0}; }, "r.every: "},
      {"repeat longer than window", [](Routine& r) { r.every = hours(11); }, "r.every: "},
      {"task longer than slot", [](Routine& r) { r.task.duration = hours(3); }, "r.task.duration: "},
      {"template with id", [](Routine& r) { r.task.id = "x"; }, "r.task.id: "},
      {"last day before first",
       [](Routine& r) {
         r.first_day = year{2026} / 2 / 1;
         r.last_day = year{2026} / 1 / 1;
       },
       "r.last_day: "},
  };
  for (const auto& c : cases) {
    Routine r = exit_checks();
    c.spoil(r);
    auto s = validate(r, "r");
    ASSERT_FALSE(s.ok()) << c.name;
    EXPECT_EQ(s.error().message.rfind(c.expect, 0), 0u) << c.name << ": " << s.error().message;
  }
  EXPECT_TRUE(validate(exit_checks()).ok());
}

}  // namespace
}  // namespace rondo
