#include "rondo/exec/clock.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace rondo::exec {
namespace {

const Time kStart = from_unix_seconds(1'700'000'000);

TEST(SimClock, RunsEventsInTimeOrderThenInSchedulingOrder) {
  SimClock clock(kStart);
  std::vector<std::string> ran;
  clock.schedule_at(kStart + seconds(20), [&] { ran.push_back("c"); });
  clock.schedule_at(kStart + seconds(10), [&] { ran.push_back("a"); });
  clock.schedule_at(kStart + seconds(10), [&] { ran.push_back("b"); });
  clock.run_until(kStart + minutes(1));
  EXPECT_EQ(ran, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(clock.now(), kStart + minutes(1));
}

TEST(SimClock, NowIsTheEventTimeInsideACallback) {
  SimClock clock(kStart);
  Time seen{};
  clock.schedule_after(seconds(42), [&] { seen = clock.now(); });
  EXPECT_TRUE(clock.step());
  EXPECT_EQ(seen, kStart + seconds(42));
  EXPECT_FALSE(clock.step());
}

TEST(SimClock, CancelledEventsDoNotRunAndCancelTwiceIsHarmless) {
  SimClock clock(kStart);
  int runs = 0;
  const TimerId id = clock.schedule_after(seconds(5), [&] { ++runs; });
  clock.cancel(id);
  clock.cancel(id);
  clock.run_until(kStart + seconds(10));
  EXPECT_EQ(runs, 0);
  EXPECT_EQ(clock.pending(), 0u);
}

TEST(SimClock, CallbacksMayScheduleMoreEventsAndPastTimesRunNow) {
  SimClock clock(kStart);
  std::vector<Time> times;
  clock.schedule_after(seconds(1), [&] {
    times.push_back(clock.now());
    clock.schedule_at(kStart, [&] { times.push_back(clock.now()); });  // in the past: runs now
  });
  clock.run_until(kStart + seconds(3));
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[0], kStart + seconds(1));
  EXPECT_EQ(times[1], kStart + seconds(1));
}

TEST(SimClock, RunUntilLeavesLaterEventsPending) {
  SimClock clock(kStart);
  int runs = 0;
  clock.schedule_after(hours(2), [&] { ++runs; });
  clock.run_until(kStart + hours(1));
  EXPECT_EQ(runs, 0);
  EXPECT_EQ(clock.pending(), 1u);
  clock.run_until(kStart + hours(2));
  EXPECT_EQ(runs, 1);
}

}  // namespace
}  // namespace rondo::exec
