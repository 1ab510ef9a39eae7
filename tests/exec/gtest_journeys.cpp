// The one journey path (docs/executor.md, "Journeys"): the executor's own journeys (to the dock
// when idle, to charge, out of service) go through the same NavigateStep as a task's, with the
// navigation monitor, the failed-edge limit, the blocked-edge policy and the live model, and write
// robot events (`departed`, `arrived`, `waits`, `gave up`, `stopped`).
//
// On the scripted robot, with models fitted on a history in which Hall_Dock is closed every day
// from 10:00 for 40 minutes (closure_models.h); and on the simulated building, with the dock's only
// way closed for two hours and no history at all.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "closure_models.h"
#include "rondo/store/events.h"
#include "rondo/store/traversal_log.h"
#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

// The robot events named `event`, in order.
std::vector<store::Event> robot_events(const store::Store& store, const std::string& event) {
  std::vector<store::Event> out;
  const std::vector<store::Event> all = store::read_events(store).value();
  for (const store::Event& e : all)
    if (e.subject == store::Subject::kRobot && e.event == event) out.push_back(e);
  return out;
}

struct HomeBlocked : ScriptedExecutor {
  explicit HomeBlocked(ExecutorOptions::BlockedEdge policy, int max_failed_edges = 25)
      : ScriptedExecutor(options_with(policy, max_failed_edges), scenario_map(), parts()) {}
  static ExecutorOptions options_with(ExecutorOptions::BlockedEdge policy, int max_failed_edges) {
    ExecutorOptions o;
    o.blocked_edge = policy;
    o.max_failed_edges = max_failed_edges;
    return o;
  }
  static ExecutorParts parts() {
    static const map::TopoMap map = scenario_map();
    ExecutorParts p;
    p.models = models_where_edge_stays_closed(map, TimeZone::named("Europe/London").value(), "Hall_Dock", 10);
    return p;
  }
  Time now() const { return clock_.now(); }
  // Answers the robot until `until`: every edge takes 20 s and succeeds, except Hall_Dock from
  // 10:00 to 10:40, which fails (the closure); every action succeeds. Counts the closure's attempts.
  void answer_until(const std::string& until) {
    const Time end = at(until);
    while (now() < end) {
      settle();
      if (robot().driving()) {
        const bool closed = robot().calls.back().starts_with("drive Hall_Dock ") && now() >= at("10:00") &&
                            now() < at("10:40");
        closure_attempts += closed ? 1 : 0;
        clock_.run_until(now() + seconds(20));
        robot().finish_edge(closed ? EdgeOutcome::kFailed : EdgeOutcome::kSucceeded, seconds(20));
      } else if (robot().acting()) {
        robot().finish_action(ActionOutcome::kSucceeded, "");
      } else {
        clock_.run_until(std::min(end, now() + seconds(20)));
      }
    }
  }
  // A task at the Office from 10:00: the robot is there, and idle, inside the closure.
  void work_at_the_office_then_go_home() {
    ASSERT_TRUE(fleet().add_task(task("A", "Office", at("10:00"), at("10:30"), minutes(1)), "test").ok());
    fleet().start();
    answer_until("10:45");
    ASSERT_EQ(state("A"), "succeeded");
  }
  int closure_attempts = 0;
};

TEST(Journeys, AnIdleJourneyHomeThatFindsItsWayBlockedWaitsForItWithRobotEvents) {
  HomeBlocked s(ExecutorOptions::BlockedEdge::kWait);
  ASSERT_NO_FATAL_FAILURE(s.work_at_the_office_then_go_home());
  // One attempt a journey: the live model holds the way blocked after it, as for a task, and the
  // robot waits at the Hall until the first quarter hour at which the model expects it to pass
  // (10:15, 10:30 and 10:45 in the 40-minute closure).
  const std::vector<store::Event> waits = robot_events(s.store(), "waits");
  EXPECT_EQ(static_cast<std::size_t>(s.closure_attempts), waits.size());
  EXPECT_LE(s.closure_attempts, 3);
  ASSERT_FALSE(waits.empty());
  EXPECT_EQ(waits.front().code, "no route now");
  EXPECT_THAT(waits.front().reason, HasSubstr("the journey to Dock (idle: back to the dock) waits at Hall"));
  EXPECT_THAT(waits.front().reason, HasSubstr("Hall_Dock"));
  // After the closure it goes home, and says so.
  s.answer_until("12:00");
  EXPECT_EQ(s.robot().location(), *s.map().find_node("Dock"));
  const std::vector<store::Event> departed = robot_events(s.store(), "departed");
  ASSERT_FALSE(departed.empty());
  EXPECT_THAT(departed.front().reason, HasSubstr("to Dock (idle: back to the dock) from Office"));
  EXPECT_EQ(departed.front().code, "departed");
  ASSERT_EQ(robot_events(s.store(), "arrived").size(), 1u);
  EXPECT_THAT(robot_events(s.store(), "arrived").front().reason, HasSubstr("at Dock (idle: back to the dock) after"));
}

TEST(Journeys, UnderGiveUpAnIdleJourneyHomeGivesUpAtTheFirstBlockedEdgeAndLooksAgainLater) {
  HomeBlocked s(ExecutorOptions::BlockedEdge::kGiveUp);
  ASSERT_NO_FATAL_FAILURE(s.work_at_the_office_then_go_home());
  const std::vector<store::Event> gave_up = robot_events(s.store(), "gave up");
  ASSERT_FALSE(gave_up.empty());
  EXPECT_EQ(gave_up.front().code, "no route now");
  EXPECT_THAT(gave_up.front().reason, HasSubstr("Hall_Dock failed"));
  // One attempt per journey, and a journey at most every slot (15 min) in the 40-minute closure.
  EXPECT_GE(s.closure_attempts, 1);
  EXPECT_LE(s.closure_attempts, 3);
}

TEST(Journeys, UnderRetryAnIdleJourneyHomeStopsAtTheFailedEdgeLimit) {
  HomeBlocked s(ExecutorOptions::BlockedEdge::kRetry, 3);
  ASSERT_NO_FATAL_FAILURE(s.work_at_the_office_then_go_home());
  const std::vector<store::Event> gave_up = robot_events(s.store(), "gave up");
  ASSERT_FALSE(gave_up.empty());
  EXPECT_EQ(gave_up.front().code, "navigation gave up");
  EXPECT_THAT(gave_up.front().reason, HasSubstr("3 failed edge attempts"));
  // Three attempts per journey, a journey at most every slot: before the one path, the first
  // journey alone tried until the limit, and the executor left again at once after each.
  EXPECT_LE(s.closure_attempts, 3 * 3);
}

TEST(Journeys, AnOwnJourneyIsWatchedByTheNavigationMonitor) {
  ScriptedExecutor s;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(1)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.settle();
  ASSERT_TRUE(s.robot().acting());
  s.robot().finish_action(ActionOutcome::kSucceeded, "");
  s.settle();
  ASSERT_TRUE(s.robot().driving());  // home: Office_Hall, and it never ends
  ASSERT_EQ(s.robot().calls.back(), "drive Office_Hall +1");
  s.clock().run_until(s.clock().now() + minutes(5));  // the limit: 2 x 40 s + 60 s
  ASSERT_EQ(s.robot().calls.back(), "cancel");
  const std::vector<store::Event> gave_up = robot_events(s.store(), "gave up");
  ASSERT_EQ(gave_up.size(), 1u);
  EXPECT_EQ(gave_up.front().code, "navigation overrun");
  EXPECT_THAT(gave_up.front().reason, HasSubstr("gave up at Office: navigation overrun"));
  EXPECT_FALSE(s.robot().driving());  // it looks again a slot (15 min) after it gave up
  s.clock().run_until(s.clock().now() + minutes(13));
  EXPECT_TRUE(s.robot().driving());
}

TEST(Journeys, AJourneyHomeStoppedForATaskSaysSo) {
  ScriptedExecutor s;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(1)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.settle();
  s.robot().finish_action(ActionOutcome::kSucceeded, "");
  s.settle();
  ASSERT_TRUE(s.robot().driving());
  ASSERT_TRUE(s.fleet().add_task(on_demand("B", "Kitchen", minutes(1)), "test").ok());
  s.settle();
  EXPECT_TRUE(s.robot().asked("cancel"));
  ASSERT_EQ(robot_events(s.store(), "stopped").size(), 1u);
  EXPECT_THAT(robot_events(s.store(), "stopped").front().reason, HasSubstr("the journey to Dock"));
  EXPECT_EQ(s.state("B"), "navigating");
}

// The simulated building: the dock's only way is closed from 10:00 to 12:00, and the robot has no
// history of it. Before the one journey path, the idle robot tried Hall_Dock 25 times, gave up,
// and tried 25 times again every 15 minutes: about 200 failed attempts in the two hours.
constexpr const char* kDockClosedWorld = R"(
kind: parametric
speed: 0.5
failure_probability: 0
noise: {sigma: 0, tail_probability: 0}
failed_duration: {min_factor: 0.2, max_factor: 0.2}
actions:
  default: {sigma: 0, failure_probability: 0, overrun_probability: 0}
effects:
  - name: the dock's corridor closed
    edges: [Hall_Dock, Dock_Hall]
    when: {days: daily, from: "10:00", to: "12:00"}
    closed: true
)";

TEST(Journeys, OnTheSimulatedBuildingTheIdleRobotDoesNotHammerTheClosedWayHome) {
  Scenario s(kDockClosedWorld);
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("10:00"), s.at("10:20"), minutes(5)), "test").ok());
  s.fleet().start();
  s.run_until("13:00");
  EXPECT_EQ(s.final_state("A"), "succeeded");
  std::vector<Traversal> log = store::find_traversals(s.store()).value();
  const auto in_closure = [&](const Traversal& t) {
    return t.edge_id == "Hall_Dock" && t.start >= s.at("10:00") && t.start < s.at("12:00");
  };
  const auto failed = std::count_if(log.begin(), log.end(), [&](const Traversal& t) { return in_closure(t) && !t.success; });
  // Two failures in the first probe (the run refutes the live model, which has no history), then
  // one a probe, since the run of failures is the executor's, not the journey's; a probe a quarter
  // hour: 9 in the two hours (16 while the run was the journey's), where each journey alone used
  // to try 25 times.
  EXPECT_GE(failed, 1);
  EXPECT_LE(failed, 16);
  std::vector<store::Event> ends = robot_events(s.store(), "waits");
  const std::vector<store::Event> gave_up = robot_events(s.store(), "gave up");
  ends.insert(ends.end(), gave_up.begin(), gave_up.end());
  EXPECT_FALSE(ends.empty());
  // Home after the closure.
  EXPECT_EQ(s.robot().location(), *s.map().find_node("Dock"));
  EXPECT_FALSE(robot_events(s.store(), "arrived").empty());
}

}  // namespace
}  // namespace rondo::exec::testing
