// Drops for now and on-demand tasks, fleet-wide (issue 38): a task one robot drops for now goes to a
// robot whose schedule it fits, or waits until one is free; an on-demand task goes to the nearest
// free robot, and when none is free, interrupts the lowest-priority interruptible task. The fleet
// says why it chose each robot.
#include <gtest/gtest.h>

#include <algorithm>

#include "fleet_fixture.h"
#include "rondo/store/events.h"

namespace rondo::fleet::testing {
namespace {

using exec::testing::on_demand;
using exec::testing::task;

// The reasons of `id`'s events of kind `kind`, in order.
std::vector<std::string> reasons(ScriptedFleet& f, const std::string& id, const std::string& kind) {
  std::vector<std::string> out;
  const std::vector<store::Event> events = store::read_events_of(f.store(), id).value();
  for (const store::Event& e : events)
    if (e.event == kind) out.push_back(e.reason);
  return out;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

Task own(Task t, const std::string& robot) {
  t.robot = robot;
  return t;
}

// r1 stands at the Office with a task of its own there, 09:00-09:30; `low` fits after it, until a
// person moves low's deadline to 09:30. `low` names r1 when `pinned`.
struct Squeezed {
  ScriptedFleet f{{{"r1", "Office"}, {"r2", "Dock"}}};
  explicit Squeezed(bool pinned) {
    f.fleet().start();
    EXPECT_TRUE(f.fleet()
                    .add_task(own(task("high", "Office", f.at("09:00"), f.at("09:30"), minutes(25), 5), "r1"), "test")
                    .ok());
    Task low = task("low", "Office", f.at("09:00"), f.at("10:00"), minutes(20), 0);
    if (pinned) low.robot = "r1";
    EXPECT_TRUE(f.fleet().add_task(low, "test").ok());
    EXPECT_EQ(f.robot_of("low"), "r1") << "it fits after high, where it stands";
    f.settle();
    EXPECT_TRUE(f.fleet().update_task("low", TimeWindow{f.at("09:00"), f.at("09:30")}, std::nullopt).ok());
    f.settle();
  }
};

TEST(FleetDrops, ATaskItsRobotDropsForNowMovesToARobotWhereItFits) {
  Squeezed s(false);
  ScriptedFleet& f = s.f;
  EXPECT_EQ(f.robot_of("low"), "r2");
  ASSERT_EQ(reasons(f, "low", "dropped for now").size(), 1u) << "r1 dropped it";
  const std::vector<std::string> moved = reasons(f, "low", "re-allocated");
  ASSERT_EQ(moved.size(), 1u);
  EXPECT_TRUE(contains(moved[0], "from r1 (dropped for now there: ")) << moved[0];
  EXPECT_TRUE(contains(moved[0], "to r2: the only robot that may take it")) << moved[0];
  const exec::Executor::Activity r2 = f.fleet().find_robot("r2")->activity();
  EXPECT_EQ(r2.planned, std::vector<TaskId>{"low"}) << "r2 planned it";
  EXPECT_FALSE(f.fleet().book().at("low").dropped_for_now);
  EXPECT_TRUE(f.fleet().book().at("low").planned_start.has_value());
}

TEST(FleetDrops, ADropThatFitsNoOtherRobotWaitsUntilOneIsFree) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Office"}});
  f.fleet().start();
  // Both robots work at the Office until 10:00.
  ASSERT_TRUE(f.fleet().add_task(own(task("p1", "Office", f.at("08:00"), f.at("10:00"), hours(2)), "r1"), "test").ok());
  ASSERT_TRUE(f.fleet().add_task(own(task("p2", "Office", f.at("08:00"), f.at("10:00"), hours(2)), "r2"), "test").ok());
  f.settle();
  ASSERT_TRUE(f.robot(0).acting() && f.robot(1).acting());
  ASSERT_TRUE(f.fleet().add_task(task("y", "Office", f.at("08:00"), f.at("09:30"), minutes(20)), "test").ok());
  f.settle();
  const std::string first = f.robot_of("y");
  EXPECT_TRUE(f.fleet().book().at("y").dropped_for_now) << "it fits neither robot's schedule";
  EXPECT_TRUE(reasons(f, "y", "re-allocated").empty()) << "no robot has room: it stays where it is";
  // The other robot's work is cancelled: it is free, and takes `y`.
  const std::string other_task = first == "r1" ? "p2" : "p1";
  const std::string other = first == "r1" ? "r2" : "r1";
  ASSERT_TRUE(f.fleet().cancel_task(other_task, "not needed").ok());
  f.settle();
  EXPECT_EQ(f.robot_of("y"), other);
  const std::vector<std::string> moved = reasons(f, "y", "re-allocated");
  ASSERT_EQ(moved.size(), 1u);
  EXPECT_TRUE(contains(moved[0], "from " + first + " (dropped for now there")) << moved[0];
  EXPECT_TRUE(f.robot(first == "r1" ? 1 : 0).acting()) << "it runs y at once";
  EXPECT_EQ(f.fleet().book().at("y").state, TaskState::kActing);
}

TEST(FleetDrops, ATaskNamingItsRobotStaysDroppedThere) {
  Squeezed s(true);
  ScriptedFleet& f = s.f;
  EXPECT_EQ(f.robot_of("low"), "r1");
  EXPECT_TRUE(f.fleet().book().at("low").dropped_for_now);
  EXPECT_TRUE(reasons(f, "low", "re-allocated").empty());
}

TEST(FleetOnDemand, GoesToTheNearestFreeRobotRatherThanInterruptingOne) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Dock"}});
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_task(own(task("a", "Office", f.at("08:00"), f.at("10:00"), hours(1)), "r1"), "test").ok());
  f.settle();
  ASSERT_TRUE(f.robot(0).acting());
  ASSERT_TRUE(f.fleet().add_task(on_demand("now", "Office", minutes(5)), "test").ok());
  f.settle();
  EXPECT_EQ(f.robot_of("now"), "r2") << "r1 stands there, but works";
  EXPECT_TRUE(f.robot(0).acting()) << "a is not interrupted";
  EXPECT_EQ(f.fleet().book().at("a").state, TaskState::kActing);
  const std::vector<std::string> why = reasons(f, "now", "allocated");
  ASSERT_EQ(why.size(), 1u);
  EXPECT_TRUE(contains(why[0], "to r2: of the free robots it can be there soonest")) << why[0];
}

TEST(FleetOnDemand, WhenNoRobotIsFreeInterruptsTheLowestPriorityTask) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Dock"}, {"r3", "Kitchen"}});
  f.fleet().start();
  ASSERT_TRUE(
      f.fleet().add_task(own(task("a", "Office", f.at("08:00"), f.at("10:00"), hours(1), 3), "r1"), "test").ok());
  ASSERT_TRUE(f.fleet().add_task(own(task("b", "Dock", f.at("08:00"), f.at("10:00"), hours(1), 1), "r2"), "test").ok());
  ASSERT_TRUE(f.fleet()
                  .add_task(own(task("c", "Kitchen", f.at("08:00"), f.at("10:00"), hours(1), 0, false), "r3"), "test")
                  .ok());
  f.settle();
  ASSERT_TRUE(f.robot(0).acting() && f.robot(1).acting() && f.robot(2).acting());
  ASSERT_TRUE(f.fleet().add_task(on_demand("now", "Office", minutes(5)), "test").ok());
  f.settle();
  // c has the lowest priority, but cannot be interrupted; b can, and is below a.
  EXPECT_EQ(f.robot_of("now"), "r2");
  EXPECT_EQ(f.fleet().book().at("b").outcome, exec::Outcome::kPreemptedOnDemand);
  EXPECT_NE(f.fleet().book().at("b").state, TaskState::kActing);
  EXPECT_EQ(f.fleet().book().at("a").state, TaskState::kActing);
  EXPECT_EQ(f.fleet().book().at("c").state, TaskState::kActing);
  const std::vector<std::string> why = reasons(f, "now", "allocated");
  ASSERT_EQ(why.size(), 1u);
  EXPECT_TRUE(contains(why[0], "to r2: no robot is free; interrupting task b (priority 1)")) << why[0];
}

// The task interrupted for an on-demand one goes back to the fleet's pool: here only r3, free in a
// minute, can still start it in its window (r2 runs the on-demand task, r1 works for an hour).
TEST(FleetOnDemand, TheInterruptedTaskGoesBackToTheFleetsPool) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Dock"}, {"r3", "Kitchen"}});
  f.fleet().start();
  ASSERT_TRUE(
      f.fleet().add_task(own(task("a", "Office", f.at("08:00"), f.at("10:00"), hours(1), 3), "r1"), "test").ok());
  ASSERT_TRUE(f.fleet().add_task(task("b", "Dock", f.at("08:00"), f.at("09:03"), hours(1), 1), "test").ok());
  ASSERT_TRUE(f.fleet()
                  .add_task(own(task("c", "Kitchen", f.at("08:00"), f.at("10:00"), minutes(1), 0, false), "r3"), "test")
                  .ok());
  f.settle();
  ASSERT_EQ(f.robot_of("b"), "r2");
  ASSERT_TRUE(f.robot(0).acting() && f.robot(1).acting() && f.robot(2).acting());
  ASSERT_TRUE(f.fleet().add_task(on_demand("now", "Office", minutes(5)), "test").ok());
  f.settle();
  EXPECT_EQ(f.robot_of("now"), "r2");
  EXPECT_EQ(f.robot_of("b"), "r3");
  const std::vector<std::string> why = reasons(f, "b", "re-allocated");
  ASSERT_EQ(why.size(), 1u);
  EXPECT_TRUE(contains(why[0], "from r2 (preempted by an on-demand task) to r3")) << why[0];
  f.robot(2).finish_action(exec::ActionOutcome::kSucceeded);  // c ends: r3 goes to the Dock for b
  f.clock().run_until(f.clock().now() + seconds(1));
  EXPECT_TRUE(f.robot(2).driving());
}

TEST(FleetAllocated, AFleetOfOneSaysNothingAboutItsChoice) {
  ScriptedFleet f(std::vector<ScriptedFleet::RobotAt>{{"r1", "Office"}});
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_task(task("x", "Office", f.at("09:00"), f.at("12:00"), minutes(5)), "test").ok());
  EXPECT_TRUE(reasons(f, "x", "allocated").empty());
}

}  // namespace
}  // namespace rondo::fleet::testing
