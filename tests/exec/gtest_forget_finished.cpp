// Finished tasks leave the executor's memory (ExecutorOptions::forget_finished, `rondo serve`) and
// stay in the store: every reader still finds them there, and what the executor does is the same
// as when it keeps them (`rondo run`).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rondo/store/events.h"
#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

ExecutorOptions forgetting(bool on = true) {
  ExecutorOptions o;
  o.forget_finished = on;
  return o;
}

// One task at the Office, done by the scripted robot.
void do_one(ScriptedExecutor& s, const std::string& id) {
  ASSERT_TRUE(s.fleet().add_task(task(id, "Office", s.at("08:00"), s.at("12:00"), minutes(2)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.settle();
  ASSERT_TRUE(s.robot().acting());
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
}

TEST(ForgetFinished, AFinishedTaskLeavesMemoryAndIsReadFromTheStore) {
  ScriptedExecutor s(forgetting());
  ASSERT_NO_FATAL_FAILURE(do_one(s, "a"));
  EXPECT_FALSE(s.executor().tasks().contains("a"));
  EXPECT_TRUE(s.executor().task_order().empty());
  EXPECT_EQ(s.state("a"), "succeeded");
  const auto r = s.executor().task("a");
  ASSERT_TRUE(r.ok()) << r.error().message;
  ASSERT_TRUE(r->has_value());
  EXPECT_EQ((*r)->state, TaskState::kSucceeded);
  EXPECT_EQ((*r)->outcome, Outcome::kDone);
  EXPECT_THAT((*r)->reason, HasSubstr("done"));
  EXPECT_EQ((*r)->task.start_node, "Office");
  EXPECT_TRUE((*r)->started.has_value());
  EXPECT_TRUE((*r)->ended.has_value());
  EXPECT_FALSE(s.executor().task("nobody")->has_value());
}

TEST(ForgetFinished, AFinishedTaskStillHoldsItsIdAndCannotBeCancelledOrChanged) {
  ScriptedExecutor s(forgetting());
  ASSERT_NO_FATAL_FAILURE(do_one(s, "a"));
  ASSERT_FALSE(s.executor().tasks().contains("a"));
  const Status again = s.fleet().add_task(task("a", "Lab", s.at("09:00"), s.at("12:00"), minutes(2)), "test");
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.error().code, ErrorCode::kInvalidInput);
  EXPECT_THAT(again.error().message, HasSubstr("'a' is already stored"));  // the store refuses it
  const Status cancel = s.executor().cancel_task("a", "too late");
  ASSERT_FALSE(cancel.ok());
  EXPECT_EQ(cancel.error().code, ErrorCode::kConflict);
  const Status change = s.executor().update_task("a", std::nullopt, 3);
  ASSERT_FALSE(change.ok());
  EXPECT_EQ(change.error().code, ErrorCode::kConflict);
  EXPECT_EQ(s.executor().cancel_task("nobody", "").error().code, ErrorCode::kNotFound);
}

TEST(ForgetFinished, AfterARestartTheFinishedTasksLeaveMemoryAgain) {
  ScriptedExecutor s(forgetting());
  ASSERT_NO_FATAL_FAILURE(do_one(s, "a"));
  ASSERT_TRUE(s.fleet().add_task(task("b", "Lab", s.at("10:00"), s.at("12:00"), minutes(2)), "test").ok());
  ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
  s.settle();
  EXPECT_FALSE(s.executor().tasks().contains("a"));
  EXPECT_TRUE(s.executor().tasks().contains("b"));
  EXPECT_EQ(s.state("a"), "succeeded");
  EXPECT_FALSE(s.fleet().add_task(task("a", "Lab", s.at("09:00"), s.at("12:00"), minutes(2)), "test").ok());
}

// The event log of a day of the calm world (a preemption by an on-demand task, tasks failing and
// succeeding), as text.
std::vector<std::string> day_log(bool forget) {
  Scenario s(kCalmWorld, forgetting(forget));
  s.fleet().start();
  EXPECT_TRUE(s.fleet().add_tasks({task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(30)),
                                   task("B", "Kitchen", s.at("08:00"), s.at("11:00"), minutes(40)),
                                   task("C", "Lab", s.at("08:00"), s.at("08:45"), minutes(30))},
                                  "test"));
  s.run_until("08:10");
  EXPECT_TRUE(s.fleet().add_task(on_demand("OD", "Lab", minutes(5)), "request"));
  s.run_until("09:30");
  EXPECT_TRUE(s.fleet().add_task(task("D", "Office", s.at("09:30"), s.at("12:00"), minutes(10)), "test"));
  s.run_until("12:00");
  EXPECT_EQ(s.executor().tasks().empty(), forget) << "every task here is final by noon";
  std::vector<std::string> log;
  for (const store::Event& e : s.all_events())
    log.push_back(format_time(e.time) + " " + e.task_id + " " + e.event + " " + e.code + " " + e.reason);
  return log;
}

TEST(ForgetFinished, TheExecutorDoesTheSameWhetherItKeepsFinishedTasksOrNot) {
  const std::vector<std::string> kept = day_log(false);
  ASSERT_FALSE(kept.empty());
  EXPECT_EQ(day_log(true), kept);
}

}  // namespace
}  // namespace rondo::exec::testing
