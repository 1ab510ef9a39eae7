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

}  // namespace
}  // namespace rondo::exec
