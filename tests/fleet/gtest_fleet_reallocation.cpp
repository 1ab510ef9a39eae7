// Re-allocation (issue 38): a robot that cannot work (a fault that lasts, out of service) hands its
// unstarted tasks to the robots that can, and in a fault its running task too, with the actions it
// did; a fault that clears in time keeps them; a delivery begun on a robot stays on it; a task
// naming its robot stays.
#include <gtest/gtest.h>

#include <algorithm>

#include "fleet_fixture.h"
#include "rondo/store/events.h"

namespace rondo::fleet::testing {
namespace {

using exec::testing::task;

// The tasks `robot` holds among `ids`.
std::vector<std::string> held_by(const ScriptedFleet& f, const std::string& robot,
                                 const std::vector<std::string>& ids) {
  std::vector<std::string> out;
  for (const std::string& id : ids)
    if (f.robot_of(id) == robot) out.push_back(id);
  return out;
}

int reallocated_events(ScriptedFleet& f, const std::string& id) {
  const auto events = store::read_events_of(f.store(), id).value();
  return static_cast<int>(
      std::count_if(events.begin(), events.end(), [](const store::Event& e) { return e.event == "re-allocated"; }));
}

// Robot `i` does what it is asked, 30 s a step, until `until` (the others stand still).
void work(ScriptedFleet& f, std::size_t i, Time until) {
  while (f.clock().now() < until) {
    f.clock().run_until(f.clock().now() + seconds(30));
    ScriptedRobot& r = f.robot(i);
    if (r.driving())
      r.finish_edge(exec::EdgeOutcome::kSucceeded, seconds(30));
    else if (r.acting())
      r.finish_action(exec::ActionOutcome::kSucceeded);
  }
}

// r1 stands at the Office where four tasks are; r2 at the Dock. r1 starts the first.
struct Busy {
  ScriptedFleet f{{{"r1", "Office"}, {"r2", "Dock"}}};
  std::vector<std::string> ids{"a", "b", "c", "d"};
  Busy() {
    f.fleet().start();
    for (const std::string& id : ids)
      EXPECT_TRUE(f.fleet().add_task(task(id, "Office", f.at("08:00"), f.at("12:00"), minutes(10)), "test").ok());
    f.settle();
  }
};

TEST(FleetReallocation, ARobotFaultingMidTaskHandsItsTasksToAnotherTheRunningOneToo) {
  Busy b;
  ScriptedFleet& f = b.f;
  ASSERT_TRUE(f.robot(0).acting()) << "r1 works where it stands";
  const std::vector<std::string> r1_before = held_by(f, "r1", b.ids);
  ASSERT_GE(r1_before.size(), 2u);
  std::vector<std::string> waiting;
  for (const std::string& id : r1_before)
    if (f.fleet().book().at(id).state != TaskState::kActing) waiting.push_back(id);
  ASSERT_EQ(waiting.size(), r1_before.size() - 1) << "one runs on r1";
  f.robot(0).report_fault("motor driver");
  f.clock().run_until(f.clock().now() + minutes(1));
  EXPECT_EQ(held_by(f, "r1", b.ids), r1_before) << "not before reallocate_after (2 min)";
  f.clock().run_until(f.clock().now() + minutes(1) + seconds(1));
  // Everything r1 held went to r2, each with its event: the running one was stopped (its action
  // cancelled) and re-offered.
  EXPECT_TRUE(f.robot(0).asked("cancel"));
  for (const std::string& id : r1_before) {
    EXPECT_EQ(f.robot_of(id), "r2") << id;
    EXPECT_EQ(reallocated_events(f, id), 1) << id;
  }
  EXPECT_TRUE(f.robot(1).busy()) << "r2 is on its way to the Office";
  // r2 does them all while r1 stays in fault.
  work(f, 1, f.at("12:00"));
  for (const std::string& id : r1_before) EXPECT_EQ(f.fleet().book().at(id).state, TaskState::kSucceeded) << id;
}

// The running task keeps its progress: the action it did on r1 is not done again on r2.
TEST(FleetReallocation, AHandedBackTaskKeepsTheActionsItDid) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Dock"}});
  f.fleet().start();
  Task two = task("two", "Office", f.at("08:00"), f.at("12:00"), minutes(10));
  two.actions = {Action{.name = "open", .args = {}}, Action{.name = "check", .args = {}}};
  ASSERT_TRUE(f.fleet().add_task(two, "test").ok());
  f.settle();
  ASSERT_EQ(f.robot_of("two"), "r1");
  ASSERT_TRUE(f.robot(0).acting());
  ASSERT_TRUE(f.robot(0).asked("act open"));
  f.robot(0).finish_action(exec::ActionOutcome::kSucceeded);
  f.clock().run_until(f.clock().now() + seconds(1));
  ASSERT_TRUE(f.robot(0).asked("act check"));
  f.robot(0).report_fault("lidar");
  f.clock().run_until(f.clock().now() + minutes(3));
  EXPECT_EQ(f.robot_of("two"), "r2");
  EXPECT_EQ(f.fleet().book().at("two").actions_done, 1u);
  work(f, 1, f.at("12:00"));
  EXPECT_EQ(f.fleet().book().at("two").state, TaskState::kSucceeded);
  EXPECT_FALSE(f.robot(1).asked("act open")) << "done on r1 already";
  EXPECT_TRUE(f.robot(1).asked("act check"));
}

TEST(FleetReallocation, AFaultThatClearsInTimeKeepsTheTasks) {
  Busy b;
  ScriptedFleet& f = b.f;
  const std::vector<std::string> r1_before = held_by(f, "r1", b.ids);
  f.robot(0).report_fault("bumper pressed");
  f.clock().run_until(f.clock().now() + minutes(1));
  f.robot(0).report_ready();
  f.clock().run_until(f.clock().now() + minutes(2));
  EXPECT_EQ(held_by(f, "r1", b.ids), r1_before);
  for (const std::string& id : b.ids) EXPECT_EQ(reallocated_events(f, id), 0) << id;
}

TEST(FleetReallocation, OutOfServiceHandsTheTasksOnButATaskNamingItsRobotStays) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Dock"}});
  f.fleet().start();
  Task own = task("own", "Office", f.at("09:00"), f.at("12:00"), minutes(5));
  own.robot = "r1";
  ASSERT_TRUE(f.fleet().add_task(own, "test").ok());
  ASSERT_TRUE(f.fleet().add_task(task("x", "Office", f.at("09:00"), f.at("12:00"), minutes(5)), "test").ok());
  ASSERT_EQ(f.robot_of("x"), "r1");
  f.fleet().find_robot("r1")->set_out_of_service(true, false, "a person paused it");
  f.clock().run_until(f.clock().now() + minutes(3));
  EXPECT_EQ(f.robot_of("x"), "r2");
  EXPECT_EQ(f.robot_of("own"), "r1");
  const auto events = store::read_events_of(f.store(), "x").value();
  const auto it =
      std::find_if(events.begin(), events.end(), [](const store::Event& e) { return e.event == "re-allocated"; });
  ASSERT_NE(it, events.end());
  EXPECT_EQ(it->robot, "r2");
  EXPECT_NE(it->reason.find("from r1 (out of service"), std::string::npos) << it->reason;
  work(f, 1, f.at("10:00"));
  EXPECT_EQ(f.fleet().book().at("x").state, TaskState::kSucceeded);
  EXPECT_EQ(f.fleet().book().at("own").state, TaskState::kQueued);  // waits for r1
}

TEST(FleetReallocation, AFleetOfOneKeepsItsTasks) {
  ScriptedFleet f(std::vector<ScriptedFleet::RobotAt>{{"r1", "Office"}});
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_task(task("x", "Office", f.at("09:00"), f.at("12:00"), minutes(5)), "test").ok());
  f.robot(0).report_fault("lost");
  f.clock().run_until(f.clock().now() + minutes(5));
  EXPECT_EQ(f.robot_of("x"), "r1");
  EXPECT_EQ(reallocated_events(f, "x"), 0);
}

}  // namespace
}  // namespace rondo::fleet::testing
