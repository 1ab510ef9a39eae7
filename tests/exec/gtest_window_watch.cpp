// The window watch (ExecutorOptions::navigation_window) against a robot the test answers by hand:
// under the chance constraint a journey past its monitor's limit goes on while its task can still
// start in its window, unless the learned laws of the edge in progress say that an attempt
// running this long is more likely a failure (docs/executor.md, "The window watch").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "rondo/plan/learned_edge_models.h"
#include "rondo/store/events.h"
#include "steps.h"
#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

// The scenario map's models: every attempt succeeds with probability 0.9, with pooled attempt
// laws (multiples of each edge's expected attempt time), as the nightly refit would set them
// under risk_alpha.
std::shared_ptr<plan::LearnedEdgeModels> models_with(const map::TopoMap& map, plan::AttemptLaws laws) {
  auto models =
      std::make_shared<plan::LearnedEdgeModels>(map, nullptr, plan::DistancePriorOptions{.success_probability = 0.9});
  models->set_attempt_laws(std::make_shared<const plan::AttemptLaws>(std::move(laws)));
  return models;
}

// A to the Office (08:00 to 10:00, 5 minutes): the robot crosses Dock_Hall in 20 s and then stays
// on Hall_Office, unanswered, until 08:10, far past the journey's monitor limit.
void hold_the_last_edge(ScriptedExecutor& s) {
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("10:00"), minutes(5)), "test").ok());
  s.fleet().start();
  s.settle();
  ASSERT_TRUE(s.robot().driving());
  s.clock().run_until(s.clock().now() + seconds(20));
  s.robot().finish_edge(EdgeOutcome::kSucceeded, seconds(20));
  s.settle();
  ASSERT_TRUE(s.robot().driving());
  EXPECT_EQ(s.robot().calls.back(), "drive Hall_Office +0");
  s.run_until("08:10");
}

// The monitor at the expected time or the median, so that its limit is not the laws' tail itself.
const ExecutorOptions kRisk{
    .navigation_overrun = 1.0, .navigation_slack = Duration{0}, .risk_alpha = 0.1, .navigation_alpha = 0.5};

// Successes take their expected time, failures twelve times as long: an attempt still running at
// the limit is a failure by the laws, so the watch stops it there as the monitor always did.
TEST(WindowWatch, AnAttemptTheLawsCallAFailureIsStoppedAtTheLimit) {
  const map::TopoMap map = scenario_map();
  ScriptedExecutor s(kRisk, map,
                     ExecutorParts{.models = models_with(map, {.success = {{1.0, 1.0}}, .failure = {{12.0, 1.0}}})});
  ASSERT_NO_FATAL_FAILURE(hold_the_last_edge(s));

  EXPECT_EQ(s.state("A"), "failed");
  EXPECT_EQ(s.code_of("A", "failed"), "navigation overrun");
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("an attempt of Hall_Office still running after"));
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("is more likely to fail, by its learned attempt times"));
  EXPECT_EQ(s.code_of("A", "overrun"), "");  // never let go on
  EXPECT_TRUE(s.robot().asked("cancel"));
}

// A tenth of the successes take thirty times their expected time, and failures end in half: the
// attempt still running is a slow success, so the journey goes on, and A is done when the edge ends.
TEST(WindowWatch, AnAttemptTheLawsCallASlowSuccessGoesOnWhileTheWindowIsOpen) {
  const map::TopoMap map = scenario_map();
  ScriptedExecutor s(
      kRisk, map,
      ExecutorParts{.models = models_with(map, {.success = {{1.0, 0.9}, {30.0, 0.1}}, .failure = {{0.5, 1.0}}})});
  ASSERT_NO_FATAL_FAILURE(hold_the_last_edge(s));

  EXPECT_EQ(s.state("A"), "navigating") << s.reason_of("A", "failed");
  EXPECT_EQ(s.code_of("A", "overrun"), "window still open");
  EXPECT_FALSE(s.robot().asked("cancel"));
  s.robot().finish_edge(EdgeOutcome::kSucceeded, minutes(9));
  s.settle();
  EXPECT_EQ(s.state("A"), "acting");
}

// A hung navigation (issue 37 point 6): the same laws as above, and the attempt never ends. Past
// every learned attempt the laws say nothing, and the window alone let it run to 09:55; it is taken
// to hang once it has run kHangFactor x the longest learned attempt (30 x the edge's expected
// attempt time) + the slack, and stopped there as an overrun.
TEST(WindowWatch, AnAttemptFarPastEveryLearnedOneIsTakenToHangAndStopped) {
  const map::TopoMap map = scenario_map();
  auto models = models_with(map, {.success = {{1.0, 0.9}, {30.0, 0.1}}, .failure = {{0.5, 1.0}}});
  ScriptedExecutor s(kRisk, map, ExecutorParts{.models = models});
  ASSERT_NO_FATAL_FAILURE(hold_the_last_edge(s));
  EXPECT_EQ(s.code_of("A", "overrun"), "window still open");  // a slow journey is still let go on
  const Time edge_start = s.at("08:00") + seconds(20);
  const map::EdgeIndex edge = *map.find_edge("Hall_Office");
  const double longest = 30.0 * models->outcome(edge, edge_start).expected_seconds;
  const Time hangs = edge_start + from_seconds(NavigateStep::kHangFactor * longest) + kRisk.navigation_slack;
  ASSERT_LT(hangs, s.at("09:55"));
  s.run_until("09:56");

  EXPECT_EQ(s.state("A"), "failed");
  EXPECT_EQ(s.code_of("A", "failed"), "navigation overrun");
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("an attempt of Hall_Office still running after"));
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("the longest of its learned attempt times"));
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("taken to hang"));
  EXPECT_TRUE(s.robot().asked("cancel"));
  const std::vector<store::Event> events = store::read_events_of(s.store(), "A").value();
  const auto failed = std::find_if(events.begin(), events.end(), [](const store::Event& e) { return e.event == "failed"; });
  ASSERT_NE(failed, events.end());
  EXPECT_NEAR(to_seconds(failed->time - hangs), 0.0, 1.0);
}

// Without laws (no refit yet) nothing tells a slow success from a failure: the window decides.
TEST(WindowWatch, WithoutLawsTheWindowAloneDecides) {
  ScriptedExecutor s(kRisk);
  ASSERT_NO_FATAL_FAILURE(hold_the_last_edge(s));
  EXPECT_EQ(s.state("A"), "navigating");
  EXPECT_EQ(s.code_of("A", "overrun"), "window still open");
  s.run_until("09:56");  // A must start by 09:55
  EXPECT_EQ(s.state("A"), "failed");
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("can no longer be expected to start in its window"));
}

}  // namespace
}  // namespace rondo::exec::testing
