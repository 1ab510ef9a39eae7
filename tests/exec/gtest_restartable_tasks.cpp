// Restartable tasks (issue 16, point 5) on the scripted robot: after a kill and Executor::restore
// a half-run action sequence goes on after its last finished action (the navigation to the place
// runs again, the actions done do not), and a task whose every action was done when the executive
// died is not run again.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "rondo/store/task_table.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

int count(const std::vector<std::string>& calls, const std::string& call) {
  return static_cast<int>(std::count(calls.begin(), calls.end(), call));
}

Task three_actions(ScriptedExecutor& s) {
  Task a = task("A", "Office", s.at("08:00"), s.at("10:00"), minutes(6));
  a.actions = {Action{.name = "one", .args = {}}, Action{.name = "two", .args = {}}, Action{.name = "three", .args = {}}};
  return a;
}

TEST(RestartableTasks, AHalfRunActionSequenceResumesAfterItsLastFinishedAction) {
  ScriptedExecutor s;
  ASSERT_TRUE(s.fleet().add_task(three_actions(s), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  ASSERT_EQ(s.robot().calls.back(), "act one");
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  ASSERT_EQ(s.robot().calls.back(), "act two");  // killed while it runs
  ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
  EXPECT_EQ(s.executor().tasks().at("A").actions_done, 1u);
  EXPECT_EQ(s.executor().tasks().at("A").outcome, Outcome::kInterrupted);
  EXPECT_EQ(s.executor().tasks().at("A").remaining(), minutes(4));
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.settle();
  EXPECT_EQ(s.robot().calls.back(), "act two");  // not "one" again
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.robot().calls.back(), "act three");
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("A"), "succeeded");
  EXPECT_EQ(count(s.robot().calls, "act one"), 1);
  EXPECT_EQ(count(s.robot().calls, "act two"), 2);  // the one cut by the kill, and again
  EXPECT_EQ(count(s.robot().calls, "act three"), 1);
  EXPECT_EQ(store::get_task(s.store(), "A").value().progress, (Json{{"actions_done", 3}}));
}

TEST(RestartableTasks, ATaskWithEveryActionDoneIsNotRunAgainAfterARestart) {
  ScriptedExecutor s;
  ASSERT_TRUE(s.fleet().add_task(three_actions(s), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  for (int i = 0; i < 2; ++i) {
    s.robot().finish_action(ActionOutcome::kSucceeded);
    s.settle();
  }
  ASSERT_EQ(s.robot().calls.back(), "act three");
  // The executive dies after the store recorded the last action, before the task's success.
  ASSERT_TRUE(store::set_task_progress(s.store(), "A", Json{{"actions_done", 3}}).ok());
  ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
  s.settle();
  EXPECT_EQ(s.state("A"), "succeeded");
  EXPECT_EQ(s.code_of("A", "succeeded"), "done");
  EXPECT_THAT(s.reason_of("A", "succeeded"), ::testing::HasSubstr("before the restart"));
  EXPECT_EQ(count(s.robot().calls, "act three"), 1);
}

}  // namespace
}  // namespace rondo::exec::testing
