// The battery's hard threshold (ExecutorOptions::battery_threshold, docs/executor.md "Battery") on
// a ScriptedRobot (scripted_robot.h): below it an interruptible task is preempted back to the
// queue (code "charging") and the robot goes to the dock; a task that cannot be interrupted
// finishes first; nothing new starts until the battery is back at the resume level.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "rondo/store/events.h"

#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

// The code of the robot's last event named `event`; "" when there is none.
std::string robot_code(ScriptedExecutor& s, const std::string& event) {
  std::string code;
  const std::vector<store::Event> events = store::read_events(s.store()).value();
  for (const store::Event& e : events)
    if (e.subject == store::Subject::kRobot && e.event == event) code = e.code;
  return code;
}

ExecutorOptions battery_options() {
  ExecutorOptions o;
  o.battery_reserve = 0.2;
  o.battery_threshold = 0.1;
  o.battery_resume = 0.5;
  o.battery_planning = false;  // the threshold alone (planned charging: gtest_planned_charging.cpp)
  return o;
}

TEST(BatteryThreshold, InterruptsAnInterruptibleTaskAndDispatchWaitsForTheCharge) {
  ScriptedExecutor s(battery_options());
  s.robot().battery_level = 0.5;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("12:00"), minutes(10)), "test").ok());
  s.fleet().start();
  s.settle();
  ASSERT_EQ(s.robot().calls.back(), "drive Dock_Hall +1");
  // The battery falls below the threshold on the way: the next edge is cancelled at once.
  s.robot().battery_level = 0.08;
  s.run_until("08:00:20");
  s.robot().finish_edge(EdgeOutcome::kSucceeded, seconds(20));
  s.settle();
  EXPECT_TRUE(s.robot().asked("cancel"));
  EXPECT_EQ(s.state("A"), "queued");
  EXPECT_EQ(s.code_of("A", "queued"), "charging");
  EXPECT_EQ(robot_code(s, "battery low"), "charging");
  EXPECT_TRUE(s.executor().charging_for_battery());
  EXPECT_EQ(s.robot().calls.back(), "drive Hall_Dock +0");  // to the charger
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Dock"));
  // On the charger below the resume level: nothing starts, however long it takes.
  s.robot().on_charger = true;
  s.robot().battery_level = 0.3;
  s.run_until("10:00");
  EXPECT_FALSE(s.robot().busy());
  EXPECT_EQ(s.executor().current_task(), std::nullopt);
  EXPECT_EQ(s.state("A"), "queued");
  // Back at the resume level: A runs again within a slot.
  s.robot().battery_level = 0.55;
  for (int minute = 1; minute <= 16 && !s.robot().busy(); ++minute) s.run_until(fmt::format("10:{:02}", minute));
  EXPECT_FALSE(s.executor().charging_for_battery());
  EXPECT_EQ(robot_code(s, "charged"), "charging");
  EXPECT_EQ(s.executor().current_task(), std::optional<TaskId>("A"));
  EXPECT_EQ(s.robot().calls.back(), "drive Dock_Hall +1");
  const BatteryFigures f = s.executor().battery_figures();
  EXPECT_EQ(f.low_battery, 1);
  EXPECT_DOUBLE_EQ(f.lowest, 0.08);
  EXPECT_EQ(f.charges, 1);
}

TEST(BatteryThreshold, ATaskThatCannotBeInterruptedFinishesFirst) {
  ScriptedExecutor s(battery_options());
  ASSERT_TRUE(
      s.fleet()
          .add_task(task("A", "Office", s.at("08:00"), s.at("12:00"), minutes(10), 1, /*interruptible=*/false), "test")
          .ok());
  ASSERT_TRUE(s.fleet().add_task(task("B", "Lab", s.at("08:00"), s.at("12:00"), minutes(10)), "test").ok());
  s.fleet().start();
  s.settle();
  s.robot().battery_level = 0.05;
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  EXPECT_TRUE(s.executor().charging_for_battery());
  EXPECT_FALSE(s.robot().asked("cancel"));
  ASSERT_TRUE(s.robot().acting());
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("A"), "succeeded");
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Dock"));  // to the charger, not to B
  s.run_until("11:00");
  EXPECT_FALSE(s.robot().busy());
  EXPECT_EQ(s.state("B"), "queued");
}

TEST(BatteryThreshold, ATaskWhoseWindowPassesWhileCharging) {
  ScriptedExecutor s(battery_options());
  s.robot().battery_level = 0.05;  // low from the start, on the charger
  s.robot().on_charger = true;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("08:30"), minutes(10)), "test").ok());
  s.fleet().start();
  s.run_until("09:00");
  EXPECT_FALSE(s.robot().busy());
  EXPECT_EQ(robot_code(s, "battery low"), "charging");
  EXPECT_EQ(s.state("A"), "dropped");
  EXPECT_EQ(s.code_of("A", "dropped for now"), "charging");
  EXPECT_EQ(s.code_of("A", "dropped"), "charging");
}

TEST(BatteryThreshold, ZeroTurnsItOff) {
  ExecutorOptions o = battery_options();
  o.battery_threshold = 0;
  ScriptedExecutor s(o);
  s.robot().battery_level = 0.05;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("12:00"), minutes(10)), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  EXPECT_FALSE(s.executor().charging_for_battery());
  EXPECT_TRUE(s.robot().acting());
}

}  // namespace
}  // namespace rondo::exec::testing
