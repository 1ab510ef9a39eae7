// A load or unload confirmed through the executor (Executor::confirm_action, the API's
// POST /api/v1/tasks/{id}/confirm): the robot's action is ended and counts as done.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

Task loading(const std::string& id, const std::string& action, Time release, Time deadline) {
  Task t = task(id, "Office", release, deadline, minutes(20));
  t.actions = {Action{.name = action, .args = {{"object", "parcel"}}}};
  return t;
}

// The robot at the Office, running the task's one action.
void acting(ScriptedExecutor& s, const Task& t) {
  ASSERT_TRUE(s.fleet().add_task(t, "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.settle();
  ASSERT_TRUE(s.robot().acting());
}

TEST(ConfirmAction, AConfirmedLoadEndsTheActionAsDoneBeforeThePersonAtTheRobot) {
  ScriptedExecutor s;
  ASSERT_NO_FATAL_FAILURE(acting(s, loading("p", "load", s.at("08:00"), s.at("12:00"))));
  s.run_until("08:05");
  ASSERT_TRUE(s.executor().confirm_action("p", "the front desk").ok());
  s.settle();  // the robot reports its action cancelled: it counts as done
  EXPECT_FALSE(s.robot().acting());
  EXPECT_EQ(s.state("p"), "succeeded");
  EXPECT_EQ(s.code_of("p", "confirmed"), "confirmed");
  EXPECT_THAT(s.reason_of("p", "confirmed"), HasSubstr("load confirmed by the front desk"));
  EXPECT_THAT(s.reason_of("p", "succeeded"), HasSubstr("done"));
  // What the person took is learned: the load time at the Office, about 5 minutes.
  const auto times = s.executor().loading_times();
  ASSERT_EQ(times.size(), 1u);
  EXPECT_EQ(times[0].place, "Office");
  EXPECT_EQ(times[0].samples, 1u);
}

TEST(ConfirmAction, OnlyARunningLoadOrUnloadCanBeConfirmed) {
  ScriptedExecutor s;
  ASSERT_TRUE(s.fleet().add_task(loading("later", "unload", s.at("10:00"), s.at("12:00")), "test").ok());
  ASSERT_NO_FATAL_FAILURE(acting(s, task("work", "Office", s.at("08:00"), s.at("09:00"), minutes(10))));
  EXPECT_EQ(s.executor().confirm_action("work", "").error().code, ErrorCode::kConflict);  // not a load
  const Status queued = s.executor().confirm_action("later", "");
  ASSERT_FALSE(queued.ok());
  EXPECT_EQ(queued.error().code, ErrorCode::kConflict);
  EXPECT_THAT(queued.error().message, HasSubstr("is queued, not loading or unloading"));
  EXPECT_EQ(s.executor().confirm_action("nobody", "").error().code, ErrorCode::kNotFound);
  EXPECT_TRUE(s.robot().acting());  // nothing was ended
}

TEST(ConfirmAction, AConfirmationTwiceIsAConflictAndAnActionThatFailedFirstStaysFailed) {
  ScriptedExecutor s;
  ASSERT_NO_FATAL_FAILURE(acting(s, loading("d", "unload", s.at("08:00"), s.at("12:00"))));
  ScriptedExecutor t;
  ASSERT_NO_FATAL_FAILURE(acting(t, loading("e", "unload", t.at("08:00"), t.at("12:00"))));
  t.robot().finish_action(ActionOutcome::kFailed, "the person was not there");
  t.settle();
  EXPECT_EQ(t.state("e"), "failed");
  EXPECT_EQ(t.executor().confirm_action("e", "").error().code, ErrorCode::kConflict);
  ASSERT_TRUE(s.executor().confirm_action("d", "").ok());
  s.settle();
  EXPECT_EQ(s.state("d"), "succeeded");
  EXPECT_EQ(s.executor().confirm_action("d", "").error().code, ErrorCode::kConflict);
}

}  // namespace
}  // namespace rondo::exec::testing
