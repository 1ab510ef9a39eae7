// Planned charging (ExecutorOptions::battery_planning, docs/executor.md "Planned charging") on a
// ScriptedRobot (scripted_robot.h): a charge inserted before the task that would run the battery
// below the reserve, a task refused for the battery when no charge fits before it, the robot sent
// home when the way to the charger is all the battery has left above the reserve, an on-demand
// or a planned task the battery cannot afford when it is due held until a charge, and a way home
// found closed tried again less and less often.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>
#include <vector>

#include "rondo/store/events.h"

#include "closure_models.h"
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
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("18:00"), hours(3)), "test").ok());
  s.fleet().start();
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
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("10:02"), hours(2)), "test").ok());
  ASSERT_TRUE(s.fleet().add_task(task("B", "Kitchen", s.at("08:00"), s.at("18:00"), minutes(10)), "test").ok());
  s.fleet().start();
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
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("18:00"), hours(1)), "test").ok());
  s.fleet().start();
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
  s.fleet().start();
  s.settle();
  // Two hours of talking (0.2 at 0.1 an hour) from 0.3 would end below the reserve.
  ASSERT_TRUE(s.fleet().add_task(on_demand("R", "Office", hours(2)), "test").ok());
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

TEST(PlannedCharging, APlannedTaskTheBatteryNoLongerAffordsWhenItIsDueRunsAfterACharge) {
  ScriptedExecutor s(planned_options());
  s.robot().battery_level = 0.6;
  s.robot().on_charger = true;
  // An hour of work from 09:00 (0.1): planned without a charge.
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("09:00"), s.at("18:00"), hours(1)), "test").ok());
  s.fleet().start();
  s.settle();
  EXPECT_EQ(s.code_of("A", "scheduled"), "scheduled");
  EXPECT_EQ(last_reason(s, store::Subject::kSchedule, "charge planned"), "");
  // Off the charger, the battery fell more than planned (a longer night, say): at 09:00 the hour
  // of work and the way back would leave it below the reserve.
  s.robot().on_charger = false;
  s.robot().battery_level = 0.25;
  s.run_until("09:00");
  EXPECT_FALSE(s.robot().busy());
  EXPECT_EQ(s.code_of("A", "waits for the charge"), "charging");
  EXPECT_NE(s.reason_of("A", "waits for the charge").find("below the 20.0 % to keep"), std::string::npos)
      << s.reason_of("A", "waits for the charge");
  EXPECT_NE(last_reason(s, store::Subject::kRobot, "charging").find("a planned charge"), std::string::npos);
  // Charged: A leaves.
  s.robot().on_charger = true;
  s.robot().battery_level = 0.6;
  for (int minute = 1; minute <= 59 && !s.robot().busy(); ++minute) s.run_until(fmt::format("09:{:02}", minute));
  EXPECT_EQ(s.executor().current_task(), std::optional<TaskId>("A"));
}

// Fails every attempt of the edge being driven until the robot asks for none: the trip home ends.
void shut_out(ScriptedExecutor& s) {
  for (int guard = 0; guard < 20 && s.robot().driving(); ++guard) {
    s.robot().finish_edge(EdgeOutcome::kFailed, seconds(10));
    s.settle();
  }
  ASSERT_FALSE(s.robot().driving());
}

// The minute a "way home closed" reason names for the next try ("... the next try at 10:31 GMT").
Time next_try(ScriptedExecutor& s) {
  const std::string reason = last_reason(s, store::Subject::kRobot, "way home closed");
  const std::size_t at = reason.find("the next try at ");
  if (at == std::string::npos) return Time{};
  return s.at(reason.substr(at + 16, 5));
}

TEST(PlannedCharging, AWayHomeFoundClosedIsTriedAgainLessAndLessOften) {
  // The live model knows that Hall_Dock, once found closed at 10:00, stays closed a while.
  static const map::TopoMap map = scenario_map();
  ScriptedExecutor s(planned_options(), scenario_map(),
                     {.models = models_where_edge_stays_closed(map, TimeZone::named("Europe/London").value(),
                                                               "Hall_Dock", 10)});
  s.robot().battery_level = 0.8;
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("09:50"), s.at("18:00"), minutes(10)), "test").ok());
  s.fleet().start();
  for (int minute = 40; minute < 60 && !s.robot().driving(); ++minute) s.run_until(fmt::format("09:{:02}", minute));
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.run_until("10:05");
  ASSERT_TRUE(s.robot().acting());
  s.robot().finish_action(ActionOutcome::kSucceeded, "");
  s.settle();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Hall"));  // on its way home: Office -> Hall -> Dock
  ASSERT_NO_FATAL_FAILURE(shut_out(s));         // Hall -> Dock is closed
  EXPECT_NE(last_reason(s, store::Subject::kRobot, "way home closed")
                .find("Hall_Dock failed on the way to the charger (1 in a row)"),
            std::string::npos)
      << last_reason(s, store::Subject::kRobot, "way home closed");
  // Not tried again before the next try it names, at least a slot (15 minutes) later.
  const Time first = s.clock().now();
  const Time again = next_try(s);
  EXPECT_GE(again - first, minutes(14));
  s.clock().run_until(again - minutes(1));
  EXPECT_FALSE(s.robot().driving());
  s.clock().run_until(again + minutes(1));  // the reason gives the minute
  ASSERT_TRUE(s.robot().driving());
  ASSERT_NO_FATAL_FAILURE(shut_out(s));
  EXPECT_NE(last_reason(s, store::Subject::kRobot, "way home closed").find("(2 in a row)"), std::string::npos);
  // Then at least two slots later.
  const Time second = s.clock().now();
  const Time later = next_try(s);
  EXPECT_GE(later - second, minutes(29));
  s.clock().run_until(later - minutes(1));
  EXPECT_FALSE(s.robot().driving());
  s.clock().run_until(later + minutes(1));
  ASSERT_TRUE(s.robot().driving());
  // Open again: home.
  s.robot().finish_edge(EdgeOutcome::kSucceeded, seconds(20));
  s.settle();
  EXPECT_EQ(s.robot().location(), *s.map().find_node("Dock"));
}

}  // namespace
}  // namespace rondo::exec::testing
