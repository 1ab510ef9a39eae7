// The executor against a robot the test answers by hand (scripted_robot.h): the branches that a
// simulated world reaches only by chance, each asserted on what the executor asked of the robot
// and on the event log.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "rondo/schedule/default_scheduler.h"
#include "rondo/store/task_table.h"
#include "rondo/store/traversal_log.h"
#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

using Scripted = ScriptedExecutor;

TEST(ScriptedRobot, ARouteIsHandedOverWithItsHorizonAndTheRobotIsActivated) {
  Scripted s;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  s.settle();
  ASSERT_GE(s.robot().calls.size(), 2u);
  EXPECT_EQ(s.robot().calls[0], "activate");
  EXPECT_EQ(s.robot().calls[1], "drive Dock_Hall +1");  // Hall_Office is the horizon
}

TEST(ScriptedRobot, AMonitorHeldWhileTheTaskCannotBeInterruptedFiresWhenItCan) {
  Scripted s;  // action monitor: 1.5 x 5 min + 30 s = 8 min
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  ASSERT_TRUE(s.robot().acting());
  s.robot().set_interruptible(false);
  s.run_until("08:20");  // far past the limit
  EXPECT_EQ(s.state("A"), "acting");
  EXPECT_EQ(s.code_of("A", "overrun"), "overrun held");
  EXPECT_EQ(s.robot().calls.back(), "act work");  // no cancel while it cannot be interrupted
  EXPECT_FALSE(s.robot().asked("cancel"));
  s.robot().set_interruptible(true);
  s.settle();
  EXPECT_TRUE(s.robot().asked("cancel"));
  EXPECT_EQ(s.state("A"), "failed");
  EXPECT_EQ(s.code_of("A", "failed"), "action overrun");
}

// Under `retry` (under `wait`, the default, a task that can wait stops at a run of failures the
// model did not expect: SharedBlockedEdge in gtest_blocked_edge.cpp).
TEST(ScriptedRobot, NavigationGivesUpAfterMaxFailedEdges) {
  Scripted s({.max_failed_edges = 3, .blocked_edge = ExecutorOptions::BlockedEdge::kRetry});
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  for (int i = 0; i < 3; ++i) {
    s.settle();
    ASSERT_TRUE(s.robot().driving()) << i;
    s.robot().finish_edge(EdgeOutcome::kFailed, seconds(10));
  }
  s.settle();
  EXPECT_EQ(s.state("A"), "failed");
  EXPECT_EQ(s.code_of("A", "failed"), "navigation gave up");
  EXPECT_EQ(store::count_traversals(s.store()).value(), 3u);  // failed attempts are learning data
}

// Dock <-> Hall <-> Office, and a one-way ramp Hall -> Pit with no way back; Island has no way in.
map::TopoMap map_with_a_pit() {
  std::vector<map::Node> nodes = {{.name = "Dock", .pose = {0, 0, 0}},
                                  {.name = "Hall", .pose = {10, 0, 0}},
                                  {.name = "Office", .pose = {20, 0, 0}},
                                  {.name = "Pit", .pose = {10, -10, 0}},
                                  {.name = "Island", .pose = {50, 0, 0}}};
  std::vector<map::Edge> edges;
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{{"Dock", "Hall"}, {"Hall", "Office"}}) {
    edges.push_back({.id = a + "_" + b, .from = a, .to = b, .action = "move_base"});
    edges.push_back({.id = b + "_" + a, .from = b, .to = a, .action = "move_base"});
  }
  edges.push_back({.id = "Hall_Pit", .from = "Hall", .to = "Pit", .action = "move_base"});
  edges.push_back({.id = "Island_Hall", .from = "Island", .to = "Hall", .action = "move_base"});
  return map::TopoMap::build("pit", std::move(nodes), std::move(edges)).value();
}

TEST(ScriptedRobot, NoRouteLeftFromWhereTheRobotEndedUpFailsTheTask) {
  Scripted s({}, map_with_a_pit());
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  s.settle();
  ASSERT_EQ(s.robot().calls.back(), "drive Dock_Hall +1");
  s.robot().move_to(*map_with_a_pit().find_node("Pit"));  // the vehicle slid down the ramp
  s.robot().finish_edge(EdgeOutcome::kFailed, seconds(15));
  s.settle();
  EXPECT_EQ(s.state("A"), "failed");
  EXPECT_EQ(s.code_of("A", "failed"), "no route");
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("from Pit to Office"));
}

TEST(ScriptedRobot, AnOnDemandTaskWithNoRouteFailsAtOnce) {
  Scripted s({}, map_with_a_pit());
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_task(on_demand("OD", "Island", minutes(2)), "request").ok());
  s.settle();
  EXPECT_EQ(s.state("OD"), "failed");
  EXPECT_EQ(s.code_of("OD", "failed"), "no route");
  EXPECT_THAT(s.reason_of("OD", "failed"), HasSubstr("Island"));
}

TEST(ScriptedRobot, ALongWaitIsSpentOnTheDockWithoutMoving) {
  Scripted s;  // dock_when_waiting_over: 15 min
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("10:00"), s.at("11:00"), minutes(5)), "test").ok());
  s.fleet().start();
  s.run_until("09:50");
  EXPECT_EQ(s.robot().calls, (std::vector<std::string>{"activate"}));  // nothing asked while it waits
  EXPECT_EQ(s.state("A"), "queued");
  s.run_until("10:00");
  EXPECT_EQ(s.robot().calls.back(), "drive Dock_Hall +1");  // leaves in time to arrive at 10:00
}

TEST(ScriptedRobot, ATripToTheDockIsCancelledForANewTask) {
  Scripted s;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  ASSERT_EQ(s.state("A"), "succeeded");
  ASSERT_EQ(s.robot().calls.back(), "drive Office_Hall +1");  // home to the dock
  const std::size_t before = s.robot().calls.size();
  ASSERT_TRUE(s.fleet().add_task(on_demand("OD", "Kitchen", minutes(2)), "request").ok());
  s.settle();
  ASSERT_TRUE(s.robot().driving());
  // The trip home is cancelled, then the robot sets off for the kitchen from where it stopped.
  EXPECT_EQ(std::vector<std::string>(s.robot().calls.begin() + static_cast<std::ptrdiff_t>(before), s.robot().calls.end()),
            (std::vector<std::string>{"cancel", "drive Office_Hall +1"}));
  EXPECT_EQ(s.state("OD"), "navigating");
  const std::vector<Traversal> log = store::find_traversals(s.store()).value();
  for (const Traversal& t : log) EXPECT_TRUE(t.success) << "a cancelled attempt is not learning data: " << t.edge_id;
}

TEST(ScriptedRobot, AnActionTheRobotStopsByItselfFailsTheTask) {
  Scripted s;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.robot().finish_action(ActionOutcome::kCancelled, "emergency stop pressed");
  s.settle();
  EXPECT_EQ(s.state("A"), "failed");
  EXPECT_EQ(s.code_of("A", "failed"), "action failed");
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("stopped by the robot"));
}

TEST(ScriptedRobot, AFaultInTheMiddleOfAnEdgePausesUntilTheRobotIsReady) {
  Scripted s;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  s.settle();
  s.run_until("08:00:05");
  s.robot().report_fault("lost connection");
  s.robot().finish_edge(EdgeOutcome::kRobotFault, seconds(5));
  s.run_until("08:30");
  EXPECT_TRUE(s.executor().paused());
  EXPECT_FALSE(s.robot().driving());  // nothing new while in fault
  EXPECT_EQ(store::count_traversals(s.store()).value(), 0u);
  EXPECT_EQ(s.code_of("A", "edge"), "robot fault");
  s.robot().report_ready();
  s.settle();
  EXPECT_TRUE(s.robot().driving());  // goes on from where the robot is
  EXPECT_EQ(s.robot().calls.back(), "drive Dock_Hall +1");
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("A"), "succeeded");
}

TEST(ScriptedRobot, CancellingARunningTaskThatCannotBeInterruptedWaitsForTheRobot) {
  Scripted s;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.robot().set_interruptible(false);
  s.settle();
  ASSERT_TRUE(s.executor().cancel_task("A", "not needed").ok());
  EXPECT_EQ(s.code_of("A", "cancel pending"), "cancel pending");
  EXPECT_EQ(s.robot().calls.back(), "act work");
  EXPECT_FALSE(s.robot().asked("cancel"));
  s.robot().set_interruptible(true);
  s.settle();
  EXPECT_TRUE(s.robot().asked("cancel"));
  EXPECT_EQ(s.state("A"), "cancelled");
}

TEST(ScriptedRobot, ATaskThatEndsElsewhereIsDrivenThereAfterItsActions) {
  Scripted s;
  Task a = task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5));
  a.end_node = "Kitchen";
  ASSERT_TRUE(s.fleet().add_task(a, "test").ok());
  s.fleet().start();
  EXPECT_EQ(s.executor().phase(), ExecutorPhase::kIdle);
  s.settle();
  EXPECT_EQ(s.executor().phase(), ExecutorPhase::kNavigating);
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  EXPECT_EQ(s.executor().phase(), ExecutorPhase::kActing);
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("A"), "navigating");  // its actions are done, but it ends at the Kitchen
  EXPECT_EQ(s.executor().phase(), ExecutorPhase::kNavigating);
  EXPECT_EQ(s.robot().calls.back(), "drive Office_Hall +1");
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Kitchen"));
  EXPECT_EQ(s.state("A"), "succeeded");
  EXPECT_THAT(s.reason_of("A", "succeeded"), HasSubstr("done: "));
  EXPECT_EQ(s.executor().current_task(), std::nullopt);
}

// A scheduler that counts its calls and asks the default one.
class CountingScheduler final : public schedule::Scheduler {
 public:
  explicit CountingScheduler(int& calls) : calls_(calls) {}
  std::string_view name() const override { return "counting"; }
  schedule::Schedule solve(const schedule::Problem& problem, const schedule::StopCondition& stop) override {
    ++calls_;
    return inner_.solve(problem, stop);
  }

 private:
  int& calls_;
  schedule::DefaultScheduler inner_;
};

TEST(ScriptedRobot, TheSchedulerAndTheModelsAreInjected) {
  int calls = 0;
  const map::TopoMap map = scenario_map();
  auto models = std::make_shared<plan::LearnedEdgeModels>(map, nullptr);
  Scripted s({}, map, ExecutorParts{.models = models, .scheduler = std::make_unique<CountingScheduler>(calls)});
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:30"), s.at("09:00"), minutes(5)), "test").ok());
  ASSERT_TRUE(s.fleet().add_task(task("B", "Lab", s.at("08:00"), s.at("10:00"), minutes(5)), "test").ok());
  s.fleet().start();
  EXPECT_GE(calls, 1);
  EXPECT_EQ(&s.executor().models(), models.get());
  EXPECT_EQ(s.executor().stats().schedules, calls);
}

TEST(ScriptedRobot, APreemptedTaskKeepsItsProgressAndGoesOnAfterTheActionsItDid) {
  Scripted s;
  Task a = task("A", "Office", s.at("08:00"), s.at("10:00"), minutes(6));
  a.actions = {Action{.name = "one", .args = {}}, Action{.name = "two", .args = {}}, Action{.name = "three", .args = {}}};
  ASSERT_TRUE(s.fleet().add_task(a, "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  EXPECT_EQ(s.robot().calls.back(), "act one");
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.robot().calls.back(), "act two");
  EXPECT_EQ(store::get_task(s.store(), "A").value().progress, (Json{{"actions_done", 1}}));
  ASSERT_TRUE(s.fleet().add_task(on_demand("OD", "Lab", minutes(5)), "request").ok());
  s.settle();  // the robot answers the preemption's cancel
  EXPECT_TRUE(s.robot().asked("cancel"));
  EXPECT_EQ(s.state("A"), "queued");
  EXPECT_EQ(s.executor().tasks().at("A").actions_done, 1u);
  EXPECT_EQ(s.executor().tasks().at("A").remaining(), minutes(4));
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Lab"));
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("OD"), "succeeded");
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  EXPECT_EQ(s.robot().calls.back(), "act two");  // not "one" again
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("A"), "succeeded");
  EXPECT_EQ(store::get_task(s.store(), "A").value().progress, (Json{{"actions_done", 3}}));
}

// The robot's busy time counts each run of a task once: a task preempted and run again adds its
// second run, not its whole span since it first started (report.json's time_s.busy).
TEST(ScriptedRobot, BusyTimeCountsEachRunOfATaskOnce) {
  Scripted s;
  Task a = task("A", "Office", s.at("08:00"), s.at("10:00"), minutes(6));
  a.actions = {Action{.name = "one", .args = {}}, Action{.name = "two", .args = {}}};
  ASSERT_TRUE(s.fleet().add_task(a, "test").ok());
  const Time start = s.clock().now();
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.clock().run_until(s.clock().now() + minutes(2));
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  ASSERT_TRUE(s.fleet().add_task(on_demand("OD", "Lab", minutes(5)), "request").ok());
  s.settle();  // A is preempted: its first run ends
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Lab"));
  s.clock().run_until(s.clock().now() + minutes(2));
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  ASSERT_EQ(s.state("OD"), "succeeded");
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.clock().run_until(s.clock().now() + minutes(2));
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  ASSERT_EQ(s.state("A"), "succeeded");
  // The robot worked without a gap from its start to A's end: A's first run, OD, A's second run.
  EXPECT_EQ(s.executor().stats().busy, s.clock().now() - start);
}

}  // namespace
}  // namespace rondo::exec::testing
