// Planned charging (ExecutorOptions::battery_planning, docs/executor.md "Planned charging") on a
// ScriptedRobot (scripted_robot.h): a charge inserted before the task that would run the battery
// below the reserve, a task refused for the battery when no charge fits before it, the robot sent
// home when the way to the charger is all the battery has left above the reserve, and an on-demand
// task the battery cannot afford held until a charge.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "rondo/store/events.h"

#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

// The last event of `subject` named `event`: its reason ("" when there is none).
std::string last_reason(ScriptedExecutor& s, store::Subject subject, const std::string& event) {
  std::string reason;
  const std::vector<store::Event> events = store::read_events(s.store()).value();
  for (const store::Event& e : events)
    if (e.subject == subject && e.event == event) reason = e.reason;
  return reason;
}

// The prior's rates with no doubt about them (0.1 per hour acting, 0.5 per hour charging, ...),
// and no margin: the figures below can be worked by hand.
ExecutorOptions planned_options() {
  ExecutorOptions o;
  o.battery_reserve = 0.2;
  o.battery_threshold = 0.1;
  o.battery_resume = 0.3;
  o.battery_planning = true;
  o.battery_margin = 0;
  return o;
}

TEST(PlannedCharging, AChargeIsInsertedBeforeTheTaskThatWouldRunTheBatteryBelowTheReserve) {
  ScriptedExecutor s(planned_options());
  s.robot().battery_level = 0.45;
  s.robot().on_charger = true;
  // Three hours of work drain about 0.3 (0.1 an hour acting): from 0.45 that ends below 0.2.
  ASSERT_TRUE(s.executor().add_task(task("A", "Office", s.at("08:00"), s.at("18:00"), hours(3)), "test").ok());
  s.executor().start();
  s.settle();
  EXPECT_FALSE(s.robot().busy());  // on the charger first
  EXPECT_NE(last_reason(s, store::Subject::kSchedule, "charge planned").find("before task A"), std::string::npos)
      << last_reason(s, store::Subject::kSchedule, "charge planned");
  EXPECT_NE(last_reason(s, store::Subject::kRobot, "charging").find("a planned charge"), std::string::npos);
  EXPECT_EQ(s.code_of("A", "scheduled"), "scheduled");
  // Charged to what the plan needs: A leaves.
  s.robot().battery_level = 0.7;
  for (int minute = 1; minute <= 60 && !s.robot().busy(); ++minute) s.run_until(fmt::format("08:{:02}", minute));
  EXPECT_NE(last_reason(s, store::Subject::kRobot, "charged").find("after the planned charge"), std::string::npos);
  EXPECT_EQ(s.executor().current_task(), std::optional<TaskId>("A"));
  EXPECT_EQ(s.robot().calls.back(), "drive Dock_Hall +1");
}

TEST(PlannedCharging, ATaskNoChargeCanSaveIsRefusedForTheBattery) {
  ScriptedExecutor s(planned_options());
  s.robot().battery_level = 0.3;
  s.robot().on_charger = true;
  // It must start at once and drains 0.2 in two hours: from 0.3 below the reserve, and there is
  // no time to charge first.
  ASSERT_TRUE(
      s.executor().add_task(task("A", "Office", s.at("08:00"), s.at("10:02"), hours(2)), "test").ok());
  ASSERT_TRUE(s.executor().add_task(task("B", "Kitchen", s.at("08:00"), s.at("18:00"), minutes(10)), "test").ok());
  s.executor().start();
  s.settle();
  EXPECT_EQ(s.code_of("A", "dropped for now"), "charging");
  // The charge it would need first leaves no room for it (or no charge fits: "the battery would fall to").
  EXPECT_NE(s.reason_of("A", "dropped for now").find("the charge the battery needs"), std::string::npos)
      << s.reason_of("A", "dropped for now");
  EXPECT_EQ(s.code_of("B", "scheduled"), "scheduled");  // the small one still fits
  s.run_until("10:30");
  EXPECT_EQ(s.state("A"), "dropped");
  EXPECT_EQ(s.code_of("A", "dropped"), "charging");
}

TEST(PlannedCharging, TheRobotGoesHomeWhenTheWayToTheChargerIsAllThatIsLeftAboveTheReserve) {
  ScriptedExecutor s(planned_options());
  s.robot().battery_level = 0.6;
  ASSERT_TRUE(s.executor().add_task(task("A", "Office", s.at("08:00"), s.at("18:00"), hours(1)), "test").ok());
  s.executor().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  ASSERT_TRUE(s.robot().acting());
  // Above the hard threshold, but at the reserve: the way back would take it below.
  s.robot().battery_level = 0.2005;
  s.run_until("08:10");
  s.robot().finish_action(ActionOutcome::kSucceeded, "");  // a robot callback: the reading
  s.settle();
  EXPECT_TRUE(s.executor().charging_for_battery());
  EXPECT_NE(last_reason(s, store::Subject::kRobot, "battery low").find("what the way to the charger needs"),
            std::string::npos)
      << last_reason(s, store::Subject::kRobot, "battery low");
}

TEST(PlannedCharging, AnOnDemandTaskTheBatteryCannotAffordRunsAfterACharge) {
  ScriptedExecutor s(planned_options());
  s.robot().battery_level = 0.3;
  s.robot().on_charger = true;
  s.executor().start();
  s.settle();
  // Two hours of talking (0.2 at 0.1 an hour) from 0.3 would end below the reserve.
  ASSERT_TRUE(s.executor().add_task(on_demand("R", "Office", hours(2)), "test").ok());
  s.settle();
  EXPECT_FALSE(s.robot().busy());
  EXPECT_EQ(s.state("R"), "queued");
  EXPECT_EQ(s.code_of("R", "waits for the charge"), "charging");
  EXPECT_NE(last_reason(s, store::Subject::kRobot, "charging").find("a planned charge"), std::string::npos);
  // Charged to what it needs (about 0.41): it runs.
  s.robot().battery_level = 0.6;
  for (int minute = 1; minute <= 16 && !s.robot().busy(); ++minute) s.run_until(fmt::format("08:{:02}", minute));
  EXPECT_EQ(s.executor().current_task(), std::optional<TaskId>("R"));
}

}  // namespace
}  // namespace rondo::exec::testing
