#include "rondo/exec/clock.h"

#include <gtest/gtest.h>

#include <atomic>
#include <string>
#include <thread>
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

TEST(SimClock, PostedCallbacksFromOtherThreadsRunBeforeTheNextEventInPostingOrder) {
  SimClock clock(kStart);
  std::vector<int> ran;
  clock.schedule_after(seconds(5), [&] { ran.push_back(-1); });
  constexpr int kEach = 200;
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t)
    threads.emplace_back([&clock, &ran, t] {
      for (int i = 0; i < kEach; ++i) clock.post([&ran, t, i] { ran.push_back(t * kEach + i); });
    });
  for (auto& th : threads) th.join();
  clock.run_until(kStart + seconds(10));
  ASSERT_EQ(ran.size(), 2u * kEach + 1);
  EXPECT_EQ(ran.back(), -1);  // the timed event came after every posted callback
  for (int t = 0; t < 2; ++t) {
    int last = -1;
    for (int v : ran)
      if (v >= t * kEach && v < (t + 1) * kEach) {
        EXPECT_GT(v, last);
        last = v;
      }
  }
}

// A fake pair of clocks for SystemClock: the test moves them; nothing waits.
struct FakeTime {
  Time wall = kStart;
  SystemClock::Steady::time_point steady{std::chrono::hours(1000)};
  SystemClock::Sources sources() {
    return {.wall = [this] { return wall; }, .steady = [this] { return steady; }};
  }
};

TEST(SystemClock, TimersRunOnTheMonotonicClockSoAWallClockStepNeitherFiresNorDelaysThem) {
  FakeTime t;
  SystemClock clock(1.0, t.sources());
  int fired = 0;
  clock.schedule_after(seconds(10), [&] { ++fired; });
  t.wall += hours(1);  // NTP steps the wall clock forward
  EXPECT_EQ(clock.run_due(), 0u);
  t.steady += std::chrono::seconds(9);
  EXPECT_EQ(clock.run_due(), 0u);
  t.steady += std::chrono::seconds(1);
  EXPECT_EQ(clock.run_due(), 1u);
  EXPECT_EQ(fired, 1);
  EXPECT_EQ(clock.now(), kStart + hours(1));  // event times stay the wall clock's UTC

  clock.schedule_after(seconds(10), [&] { ++fired; });
  t.wall -= hours(2);  // and a step backwards does not hold it back
  t.steady += std::chrono::seconds(10);
  EXPECT_EQ(clock.run_due(), 1u);
  EXPECT_EQ(fired, 2);
}

TEST(SystemClock, ASpeedFactorRunsTimeFasterForNowAndTimers) {
  FakeTime t;
  SystemClock clock(60.0, t.sources());
  int fired = 0;
  clock.schedule_after(minutes(1), [&] { ++fired; });
  t.steady += std::chrono::milliseconds(999);
  EXPECT_EQ(clock.run_due(), 0u);
  t.steady += std::chrono::milliseconds(1);
  EXPECT_EQ(clock.run_due(), 1u);
  EXPECT_EQ(clock.now(), kStart + minutes(1));
  EXPECT_THROW(SystemClock(0.0), std::invalid_argument);
}

TEST(SystemClock, PostFromTwoThreadsWakesTheLoopAndStopEndsIt) {
  SystemClock clock;
  constexpr int kEach = 500;
  std::atomic<int> count{0};
  std::vector<int> order[2];
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < kEach; ++i)
        clock.post([&, t, i] {
          order[t].push_back(i);  // runs on the clock's thread: no lock needed
          if (++count == 2 * kEach) clock.stop();
        });
    });
  // Nothing is timed: only the posts can wake the loop, and only the last one can end it. The
  // limit is far away, so a lost wake-up shows as a test time-out, never as a pass.
  clock.run_until(clock.now() + hours(1));
  for (auto& th : threads) th.join();
  EXPECT_EQ(count.load(), 2 * kEach);
  for (const auto& seen : order) {
    ASSERT_EQ(seen.size(), static_cast<std::size_t>(kEach));
    for (int i = 0; i < kEach; ++i) EXPECT_EQ(seen[static_cast<std::size_t>(i)], i);
  }
  EXPECT_TRUE(clock.stopped());
}

// `rondo serve` halts the robot and stops the clock in one posted callback: what was posted
// after it (a message from the vehicle, taken in the same batch) must not run on the executor
// after that, and stays posted instead.
TEST(SystemClock, StopEndsTheLoopAfterTheCallbackThatCalledItAndKeepsTheRestPosted) {
  SystemClock clock;
  std::vector<int> ran;
  clock.post([&] { ran.push_back(1); });
  clock.post([&] {
    ran.push_back(2);
    clock.stop();
  });
  clock.post([&] { ran.push_back(3); });
  clock.post([&] { ran.push_back(4); });
  clock.run_until(clock.now() + hours(1));
  EXPECT_EQ(ran, (std::vector<int>{1, 2}));
  clock.post([&] { ran.push_back(5); });
  clock.run_until(clock.now() + hours(1));  // stopped: returns at once
  EXPECT_EQ(ran, (std::vector<int>{1, 2}));
  EXPECT_EQ(clock.run_due(), 3u);  // in their posting order
  EXPECT_EQ(ran, (std::vector<int>{1, 2, 3, 4, 5}));
}

TEST(SystemClock, RunUntilRunsTimersAsTheyFallDue) {
  SystemClock clock(1000.0);  // a minute of clock time is 60 ms
  std::vector<int> ran;
  clock.schedule_after(seconds(30), [&] { ran.push_back(2); });
  clock.schedule_after(seconds(10), [&] { ran.push_back(1); });
  clock.run_until(clock.now() + minutes(1));
  EXPECT_EQ(ran, (std::vector<int>{1, 2}));
}

}  // namespace
}  // namespace rondo::exec
