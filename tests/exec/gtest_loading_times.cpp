// The loading times the executor learns per action and place.
#include <gtest/gtest.h>

#include "loading_times.h"

namespace rondo::exec {
namespace {

const Time kNow{};

TEST(LoadingTimes, TheDeclaredDurationUntilThePlaceHasBeenSeen) {
  LoadingTimes t;
  EXPECT_EQ(t.expected("load", "A-110-Desk", minutes(1)), minutes(1));
  t.observe("load", "A-110-Desk", minutes(1), minutes(4), true, kNow);
  // Two pseudo-observations of the declared minute and one of four minutes: two minutes.
  EXPECT_EQ(t.expected("load", "A-110-Desk", minutes(1)), minutes(2));
  EXPECT_EQ(t.expected("load", "A-114-Desk", minutes(1)), minutes(1));    // another place
  EXPECT_EQ(t.expected("unload", "A-110-Desk", minutes(1)), minutes(1));  // another action
}

TEST(LoadingTimes, OnlyTheLearnedActionsAndOnlySuccesses) {
  LoadingTimes t;
  t.observe("patrol", "Hall", minutes(1), minutes(9), true, kNow);
  EXPECT_TRUE(t.entries().empty());
  t.observe("unload", "Hall", minutes(1), minutes(9), false, kNow);
  ASSERT_EQ(t.entries().size(), 1u);
  EXPECT_EQ(t.entries()[0].samples, 0u);
  EXPECT_EQ(t.expected("unload", "Hall", minutes(1)), minutes(1));
}

TEST(LoadingTimes, ConvergeToThePersonsTime) {
  LoadingTimes t;
  for (int i = 0; i < 100; ++i) t.observe("load", "Desk", minutes(1), seconds(i % 2 == 0 ? 170 : 190), true, kNow);
  EXPECT_NEAR(to_seconds(t.expected("load", "Desk", minutes(1))), 180, 3);
}

// A slow person (300 s every time) behind the action monitor (limit 1.5 x the estimate + 30 s, as
// ExecutorOptions' defaults): a run the monitor stops is a lower bound of the person's time. Learned
// as stopped runs (censored), the estimate rises past the limit after a few stops and the runs
// complete; learned as samples of the length they had (the old rule), it creeps up and the person
// is stopped far more often.
TEST(LoadingTimes, StoppedRunsRaiseTheEstimateUntilTheSlowPersonCanFinish) {
  const Duration truth = seconds(300);
  const auto live = [&](bool censored, int& stopped) {
    LoadingTimes t;
    stopped = 0;
    for (int run = 0; run < 12; ++run) {
      const Duration limit =
          std::chrono::duration_cast<Duration>(t.expected("load", "Desk", minutes(1)) * 1.5) + seconds(30);
      if (truth <= limit) {
        t.observe("load", "Desk", minutes(1), truth, true, kNow);
      } else if (censored) {
        ++stopped;
        t.observe_stopped("load", "Desk", minutes(1), limit, kNow);
      } else {
        ++stopped;
        t.observe("load", "Desk", minutes(1), limit, true, kNow);
      }
    }
    return to_seconds(t.expected("load", "Desk", minutes(1)));
  };
  int stopped_censored = 0, stopped_old = 0;
  const double censored = live(true, stopped_censored);
  const double old = live(false, stopped_old);
  EXPECT_LE(stopped_censored, 3);  // stopped at 120 s, 180 s and 248 s; then the limit is 322 s
  EXPECT_GE(stopped_old, 2 * stopped_censored);
  EXPECT_NEAR(censored, 300, 60);
  EXPECT_LT(old, censored);
}

TEST(LoadingTimes, NoQuantileUntilEnoughRunsAreKnown) {
  LoadingTimes t;
  for (std::size_t i = 0; i + 1 < LoadingTimes::kRatioSamples; ++i)
    t.observe("load", "Desk", minutes(1), minutes(1), true, kNow);
  EXPECT_FALSE(t.quantile("load", "Desk", minutes(1), 0.98).has_value());
  t.observe("load", "Desk", minutes(1), minutes(1), true, kNow);
  ASSERT_TRUE(t.quantile("load", "Desk", minutes(1), 0.98).has_value());
  EXPECT_EQ(*t.quantile("load", "Desk", minutes(1), 0.98), minutes(1));  // everyone on time: ratio 1
}

// How much longer than expected people take is pooled over places: a place seen once gets the
// spread the others showed, scaled to its own expected time.
TEST(LoadingTimes, TheQuantileIsThePlacesExpectedTimeTimesThePooledRatio) {
  LoadingTimes t;
  // Forty runs at one desk, a person of a steady 100 s who takes 3 x that once in ten runs.
  for (int i = 0; i < 40; ++i) t.observe("load", "A", seconds(100), seconds(i % 10 == 9 ? 300 : 100), true, kNow);
  const Duration expected_a = t.expected("load", "A", seconds(100));
  EXPECT_NEAR(to_seconds(*t.quantile("load", "A", seconds(100), 0.5)), to_seconds(expected_a), 15);
  EXPECT_GT(to_seconds(*t.quantile("load", "A", seconds(100), 0.98)), 2.2 * to_seconds(expected_a));
  // A desk never seen: its declared time, times the same ratios.
  const double ratio98 = to_seconds(*t.quantile("load", "A", seconds(100), 0.98)) / to_seconds(expected_a);
  EXPECT_NEAR(to_seconds(*t.quantile("unload", "B", minutes(2), 0.98)), 120 * ratio98, 1);
}

// The action monitor's limit as ActStep sets it (ExecutorOptions' defaults: 1.5 x the estimate
// + 30 s, or the 98th percentile + 30 s when that is longer): people who are usually on time and
// once in ten runs take 2.5 x as long. With the patience the slow runs complete once the ratios
// are known; without it every one of them is stopped.
TEST(LoadingTimes, PatienceLetsTheOccasionallySlowPersonFinish) {
  const auto stops = [](double patience) {
    LoadingTimes t;
    int stopped = 0;
    for (int run = 0; run < 200; ++run) {
      const Duration truth = run % 10 == 9 ? seconds(250) : seconds(100);
      const Duration expected = t.expected("load", "Desk", seconds(100));
      Duration limit = std::chrono::duration_cast<Duration>(expected * 1.5) + seconds(30);
      if (const auto q = t.quantile("load", "Desk", seconds(100), patience); patience > 0 && q)
        limit = std::max(limit, *q + seconds(30));
      if (truth <= limit) {
        t.observe("load", "Desk", seconds(100), truth, true, kNow);
      } else {
        ++stopped;
        t.observe_stopped("load", "Desk", seconds(100), limit, kNow);
      }
    }
    return stopped;
  };
  const int without = stops(0);
  const int with = stops(0.98);
  EXPECT_GE(without, 15);
  EXPECT_LE(with, 3);
}

}  // namespace
}  // namespace rondo::exec
