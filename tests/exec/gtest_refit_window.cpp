// The executor's nightly refit reads only the traversals of the last `refit_window` (so a night
// costs the same however long the robot has lived), or the whole log when the window is unset;
// and with the online model a failed attempt reaches the planner at once.
#include <gtest/gtest.h>

#include <vector>

#include "rondo/store/traversal_log.h"
#include "scenario.h"

namespace rondo::exec::testing {
namespace {

// 200 failures of Dock_Hall a month before the scenario starts, and 20 successes the day before.
void old_and_recent_traversals(Scenario& s) {
  std::vector<Traversal> log;
  const Time start = s.at("00:00");
  for (int i = 0; i < 200; ++i)
    log.push_back({"Dock_Hall", "Dock", "Hall", start - hours(24 * 30) + minutes(5 * i), seconds(10), false, ""});
  for (int i = 0; i < 20; ++i)
    log.push_back({"Dock_Hall", "Dock", "Hall", start - hours(20) + minutes(5 * i), seconds(10), true, ""});
  ASSERT_TRUE(store::add_traversals(s.store(), log).ok());
}

int refitted_attempts(std::optional<Duration> window) {
  ExecutorOptions options;
  options.refit_window = window;
  Scenario s(kCalmWorld, options);
  old_and_recent_traversals(s);
  s.fleet().start();
  s.clock().run_until(s.at("00:00") + hours(24 + 3));  // past the refit at 02:00
  EXPECT_EQ(s.fleet().refits(), 1);
  const auto& models = s.executor().models().models();
  if (!models) return -1;
  return models->attempts(*models->index_of("Dock_Hall"));
}

TEST(RefitWindow, TheRefitReadsOnlyTheWindow) {
  EXPECT_EQ(refitted_attempts(hours(24 * 7)), 20);
  EXPECT_EQ(refitted_attempts(std::nullopt), 220);
}

TEST(RefitWindow, TheOnlineModelLearnsFromAFailedAttemptAtOnce) {
  Scenario s(kCalmWorld);
  old_and_recent_traversals(s);
  s.fleet().start();
  s.clock().run_until(s.at("00:00") + hours(24 + 3));
  const plan::LearnedEdgeModels& models = s.executor().models();
  ASSERT_EQ(models.reading(), plan::LearnedEdgeModels::Reading::kOnline);
  const map::EdgeIndex dock_hall = *s.map().find_edge("Dock_Hall");
  const Time now = s.clock().now();
  const double before = models.outcome(dock_hall, now).success_probability;
  const std::uint64_t version = models.version();
  s.executor().on_edge_finished(
      {.edge = dock_hall, .start = now - seconds(10), .duration = seconds(10), .outcome = EdgeOutcome::kFailed});
  EXPECT_EQ(models.version(), version + 1);
  EXPECT_LT(models.outcome(dock_hall, now).success_probability, before);
}

}  // namespace
}  // namespace rondo::exec::testing
