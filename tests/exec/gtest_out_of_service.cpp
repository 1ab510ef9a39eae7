// Executor::set_out_of_service on a ScriptedRobot (scripted_robot.h): the running task finishes
// or is halted back to the queue with its progress, nothing new starts, the robot docks, and back
// in service the tasks run again.
#include <gtest/gtest.h>

#include <string>

#include "rondo/store/task_table.h"
#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using Scripted = ScriptedExecutor;

Task two_actions(const std::string& id, const std::string& node, Time release, Time deadline) {
  Task t = task(id, node, release, deadline, minutes(6));
  t.actions = {Action{.name = "one", .args = {}}, Action{.name = "two", .args = {}}};
  return t;
}

TEST(OutOfService, AHaltedTaskGoesBackWithItsProgressNothingStartsAndTheRobotDocks) {
  Scripted s;
  ASSERT_TRUE(s.fleet().add_task(two_actions("A", "Office", s.at("08:00"), s.at("12:00")), "test").ok());
  ASSERT_TRUE(s.fleet().add_task(task("B", "Lab", s.at("08:40"), s.at("12:00"), minutes(5)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  ASSERT_EQ(s.robot().calls.back(), "act two");
  s.executor().set_out_of_service(true, /*halt=*/true, "lift repair");
  s.settle();
  EXPECT_TRUE(s.robot().asked("cancel"));
  EXPECT_EQ(s.state("A"), "queued");
  EXPECT_EQ(s.code_of("A", "queued"), "interrupted");
  EXPECT_EQ(s.executor().tasks().at("A").actions_done, 1u);
  EXPECT_TRUE(s.executor().out_of_service());
  // Nothing new starts: the robot goes to the dock, and neither A nor B runs while out of service.
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Dock"));
  s.run_until("09:00");
  EXPECT_FALSE(s.robot().busy());
  EXPECT_EQ(s.state("B"), "queued");
  EXPECT_EQ(s.executor().current_task(), std::nullopt);
  // Back in service: A goes on after the action it did.
  s.executor().set_out_of_service(false, false, "");
  s.settle();
  EXPECT_FALSE(s.executor().out_of_service());
  ASSERT_TRUE(s.executor().current_task().has_value());
}

TEST(OutOfService, WithoutHaltTheRunningTaskFinishesAndNothingStartsAfterIt) {
  Scripted s;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("12:00"), minutes(5)), "test").ok());
  ASSERT_TRUE(s.fleet().add_task(task("B", "Lab", s.at("08:00"), s.at("12:00"), minutes(5)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.executor().set_out_of_service(true, /*halt=*/false, "");
  s.settle();
  EXPECT_FALSE(s.robot().asked("cancel"));
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("A"), "succeeded");
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Dock"));  // to the dock, not to B
  s.run_until("09:00");
  EXPECT_EQ(s.state("B"), "queued");
  s.executor().set_out_of_service(false, false, "");
  s.settle();
  EXPECT_EQ(s.executor().current_task(), std::optional<TaskId>("B"));
}

}  // namespace
}  // namespace rondo::exec::testing
