// Allocation across a fleet of scripted robots (issue 38, "Every task belongs to at most one robot
// at a time"): the robot a task names, the robot that runs its actions, a delivery job on one
// robot, the cheapest insertion, and the tasks no robot can run.
#include <gtest/gtest.h>

#include "fleet_fixture.h"

namespace rondo::fleet::testing {
namespace {

using exec::testing::task;

Task with_action(Task t, const std::string& action) {
  t.actions = {Action{.name = action, .args = {}}};
  return t;
}

Task delivery_half(const std::string& id, const std::string& node, DeliveryRole role, Time from, Time to,
                   const std::string& job = "job1") {
  Task t = task(id, node, from, to, minutes(2));
  t.actions = {Action{.name = role == DeliveryRole::kPickup ? "load" : "unload", .args = {{"object", "book"}}}};
  t.delivery = Delivery{.job = job, .role = role, .object = "book", .appearance = "a green book"};
  return t;
}

TEST(FleetAllocation, ATaskGoesToTheRobotStandingAtItsPlace) {
  ScriptedFleet f({{"r1", "Dock"}, {"r2", "Office"}});
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_task(task("a", "Office", f.at("08:00"), f.at("12:00"), minutes(5)), "test").ok());
  ASSERT_TRUE(f.fleet().add_task(task("b", "Dock", f.at("08:00"), f.at("12:00"), minutes(5)), "test").ok());
  EXPECT_EQ(f.robot_of("a"), "r2");
  EXPECT_EQ(f.robot_of("b"), "r1");
  f.settle();
  // Each robot is given its own task only: r2 acts where it stands, r1 at the dock.
  EXPECT_TRUE(f.robot(1).acting());
  EXPECT_TRUE(f.robot(0).acting());
}

TEST(FleetAllocation, ATaskNeedingAnActionOnlyOneRobotRunsGoesToThatRobot) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Dock"}});
  f.robot(0).actions = exec::ActionSupport{.robot = "r1", .actions = {"work"}};
  f.robot(1).actions = exec::ActionSupport{.robot = "r2", .actions = {"work", "mop"}};
  f.fleet().start();
  // r1 stands at the Office, but only r2 mops.
  ASSERT_TRUE(f.fleet()
                  .add_task(with_action(task("m", "Office", f.at("08:00"), f.at("12:00"), minutes(5)), "mop"), "test")
                  .ok());
  EXPECT_EQ(f.robot_of("m"), "r2");
  // No robot sings: refused, nothing added.
  Status refused =
      f.fleet().add_task(with_action(task("s", "Office", f.at("08:00"), f.at("12:00"), minutes(5)), "sing"), "test");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(refused.error().message.find("task s:"), std::string::npos) << refused.error().message;
  EXPECT_FALSE(f.fleet().book().contains("s"));
}

TEST(FleetAllocation, ATaskNamingARobotGoesToItAndAnUnknownRobotIsRefused) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Dock"}});
  f.fleet().start();
  Task t = task("a", "Office", f.at("08:00"), f.at("12:00"), minutes(5));
  t.robot = "r2";
  ASSERT_TRUE(f.fleet().add_task(t, "test").ok());
  EXPECT_EQ(f.robot_of("a"), "r2");  // although r1 stands there
  Task u = task("b", "Office", f.at("08:00"), f.at("12:00"), minutes(5));
  u.robot = "r9";
  Status refused = f.fleet().add_task(u, "test");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message, "task b: robot 'r9' is not in this deployment (its robots are 'r1', 'r2')");
}

TEST(FleetAllocation, BothHalvesOfADeliveryGoToOneRobot) {
  ScriptedFleet f({{"r1", "Kitchen"}, {"r2", "Office"}});
  f.fleet().start();
  // The pickup is where r1 stands, the drop where r2 stands: the object stays on one robot.
  ASSERT_TRUE(f.fleet()
                  .add_tasks({delivery_half("p", "Kitchen", DeliveryRole::kPickup, f.at("08:00"), f.at("12:00")),
                              delivery_half("d", "Office", DeliveryRole::kDrop, f.at("08:00"), f.at("12:00"))},
                             "test")
                  .ok());
  EXPECT_EQ(f.robot_of("p"), f.robot_of("d"));
  EXPECT_FALSE(f.robot_of("p").empty());
}

TEST(FleetAllocation, ADeliveryPassesOverARobotCarryingALookAlike) {
  ScriptedFleet f({{"r1", "Kitchen"}, {"r2", "Dock"}});
  f.fleet().start();
  ASSERT_TRUE(f.fleet()
                  .add_tasks({delivery_half("p1", "Kitchen", DeliveryRole::kPickup, f.at("08:00"), f.at("12:00")),
                              delivery_half("d1", "Lab", DeliveryRole::kDrop, f.at("08:00"), f.at("12:00"))},
                             "test")
                  .ok());
  ASSERT_EQ(f.robot_of("p1"), "r1");
  f.settle();
  ASSERT_TRUE(f.robot(0).acting());
  f.robot(0).finish_action(exec::ActionOutcome::kSucceeded);
  f.settle();
  ASSERT_EQ(f.fleet().find_robot("r1")->on_board().size(), 1u) << "a green book on board, on its way to the Lab";
  // A second green book waits at the Kitchen too: r1 could be there soonest, but may not carry both.
  ASSERT_TRUE(
      f.fleet()
          .add_tasks({delivery_half("p2", "Kitchen", DeliveryRole::kPickup, f.at("08:00"), f.at("12:00"), "job2"),
                      delivery_half("d2", "Office", DeliveryRole::kDrop, f.at("08:00"), f.at("12:00"), "job2")},
                     "test")
          .ok());
  EXPECT_EQ(f.robot_of("p2"), "r2");
  EXPECT_EQ(f.robot_of("d2"), "r2");
}

TEST(FleetAllocation, TheRobotOfEveryTaskIsStoredAndComesBackAfterARestart) {
  ScriptedFleet f({{"r1", "Dock"}, {"r2", "Office"}});
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_task(task("a", "Office", f.at("09:00"), f.at("12:00"), minutes(5)), "test").ok());
  EXPECT_EQ(f.robot_of("a"), "r2");
  const std::vector<store::TaskRow> rows = store::list_tasks(f.store()).value();
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows.front().robot, "r2");
  f.kill_and_restart();
  EXPECT_EQ(f.robot_of("a"), "r2");
  f.clock().run_until(f.at("09:01"));
  // r2 stands at the Office and starts it there; r1 was given nothing.
  EXPECT_TRUE(f.robot(1).acting()) << ::testing::PrintToString(f.robot(1).calls);
  EXPECT_FALSE(f.robot(0).busy()) << ::testing::PrintToString(f.robot(0).calls);
}

}  // namespace
}  // namespace rondo::fleet::testing
