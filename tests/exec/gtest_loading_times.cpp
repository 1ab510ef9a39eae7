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

}  // namespace
}  // namespace rondo::exec
