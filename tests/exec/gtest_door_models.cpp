// Door-open probabilities learned by time of day (src/exec/door_models.h) from door observations
// of a simulated rhythm: the estimates converge on the truth, and a retry goes when the door is
// likely open again.
#include "door_models.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rondo::exec {
namespace {

const TimeZone& london() {
  static const TimeZone z = TimeZone::named("Europe/London").value();
  return z;
}

// The door's truth: open on weekdays 07:30-19:00 except at lunch, 12:30-13:30.
bool open_at(Time t) {
  const TimeZone& z = london();
  const auto day = z.local_date(t);
  const unsigned wd = std::chrono::weekday{std::chrono::sys_days{day}}.iso_encoding();
  const Duration tod = t - z.at(day, Duration{0});
  if (wd > 5) return false;
  if (tod < hours(7) + minutes(30) || tod >= hours(19)) return false;
  return !(tod >= hours(12) + minutes(30) && tod < hours(13) + minutes(30));
}

// Observations on `days` days from Monday 2026-11-23, at random moments 07:00-21:00 (about one
// every 20 minutes), each seen wrongly with probability 0.05.
DoorModels observed(int days, std::uint64_t seed) {
  DoorModels m(london());
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<int> gap(5, 35);
  std::bernoulli_distribution wrong(0.05);
  const Time start = london().parse_time("2026-11-23T07:00").value();
  for (int d = 0; d < days; ++d)
    for (Time t = start + hours(24 * d); t < start + hours(24 * d + 14); t += minutes(gap(rng)))
      m.observe("A-120-door", t, open_at(t) != wrong(rng));
  m.refit(start + hours(24 * days), std::nullopt);
  return m;
}

// Mean absolute error against the truth on weekday times of the grid, 08:00-18:45.
double weekday_error(const DoorModels& m) {
  const Time monday = london().parse_time("2026-12-07T08:00").value();
  double sum = 0;
  int n = 0;
  for (int d = 0; d < 5; ++d)
    for (Time t = monday + hours(24 * d); t < monday + hours(24 * d) + hours(11); t += minutes(15)) {
      sum += std::abs(m.probability("A-120-door", t).value() - (open_at(t) ? 1.0 : 0.0));
      ++n;
    }
  return sum / n;
}

TEST(DoorModels, NothingIsKnownBeforeTheFirstFit) {
  DoorModels m(london());
  const Time t = london().parse_time("2026-11-23T10:00").value();
  m.observe("A-120-door", t, true);
  EXPECT_FALSE(m.probability("A-120-door", t).has_value());
  EXPECT_FALSE(m.next_likely_open("A-120-door", t, t + hours(2), 0.5).has_value());
  EXPECT_TRUE(m.doors().empty());
}

TEST(DoorModels, TheEstimateConvergesOnTheDoorsDailyRhythm) {
  // Mean absolute errors on the weekdays after: 0.237 after a week, 0.188 after two, 0.158 after
  // four (seed 7); the one-hour bins averaged over shifted edges blur an hour's closure, so the
  // error does not go to zero.
  const double week = weekday_error(observed(7, 7));
  const double fortnight = weekday_error(observed(14, 7));
  const DoorModels month = observed(28, 7);
  EXPECT_LT(fortnight, week);
  EXPECT_LT(weekday_error(month), fortnight);
  EXPECT_LT(weekday_error(month), 0.2);
  const Time lunch = london().parse_time("2026-12-22T13:00").value();
  const Time morning = london().parse_time("2026-12-22T10:00").value();
  const Time saturday = london().parse_time("2026-12-26T10:00").value();
  EXPECT_LT(month.probability("A-120-door", lunch).value(), 0.4);
  EXPECT_GT(month.probability("A-120-door", morning).value(), 0.8);
  EXPECT_LT(month.probability("A-120-door", saturday).value(), 0.3);
}

TEST(DoorModels, TheRetryGoesWhenTheDoorIsLikelyOpenAgain) {
  const DoorModels m = observed(14, 11);
  const Time closed = london().parse_time("2026-12-08T12:35").value();
  EXPECT_LT(m.probability("A-120-door", closed).value(), 0.5);
  const auto at = m.next_likely_open("A-120-door", closed, closed + hours(3), 0.5);
  ASSERT_TRUE(at.has_value());
  EXPECT_GE(*at, london().parse_time("2026-12-08T13:15").value()) << london().format_clock(*at);
  EXPECT_LE(*at, london().parse_time("2026-12-08T14:00").value()) << london().format_clock(*at);
  // Not before the end of the window asked for.
  EXPECT_FALSE(m.next_likely_open("A-120-door", closed, closed + minutes(30), 0.5).has_value());
}

TEST(DoorModels, RepeatedLooksWithinAMinuteCountOnce) {
  DoorModels m(london());
  const Time t = london().parse_time("2026-11-23T10:00").value();
  m.observe("d", t, true);
  m.observe("d", t + seconds(20), true);
  m.observe("d", t + seconds(40), false);
  m.observe("d", t + minutes(5), false);
  EXPECT_EQ(m.samples("d"), 3u);
}

// A failed door edge is half a look at a shut door: every second one adds a "closed" sample, and
// none counts within a minute of the door's last sample (a look at the door says more).
TEST(DoorModels, AFailedDoorEdgeIsHalfALookAtAShutDoor) {
  static_assert(DoorModels::kFailedEdgeWeight == 0.5);
  DoorModels m(london());
  const Time t = london().parse_time("2026-11-23T10:00").value();
  EXPECT_FALSE(m.observe_failed_edge("d", t));
  EXPECT_TRUE(m.observe_failed_edge("d", t + minutes(5)));
  EXPECT_EQ(m.samples("d"), 1u);
  EXPECT_FALSE(m.observe_failed_edge("d", t + minutes(10)));
  m.observe("d", t + minutes(15), true);  // the sensor saw it open
  EXPECT_FALSE(m.observe_failed_edge("d", t + minutes(15) + seconds(10))) << "a look beats the failure";
  EXPECT_TRUE(m.observe_failed_edge("d", t + minutes(20)));
  EXPECT_EQ(m.samples("d"), 3u);
  EXPECT_FALSE(m.observe_failed_edge("e", t)) << "the credit is per door";
  m.refit(t + hours(1), std::nullopt);
  ASSERT_TRUE(m.probability("d", t + minutes(20)).has_value());
}

}  // namespace
}  // namespace rondo::exec
