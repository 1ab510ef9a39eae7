// Traffic on scripted robots (issue 42; docs/traffic.md): the robots reserve their way through the
// scenario map's one hall, whose every room is a dead end. Two robots that want each other's room
// meet head-on: one is sent aside and both tasks are done; a robot waiting for its task's window
// in the hall is parked there, and makes way for one that has to pass. Never two robots on a node.
// Planning around each other: a robot whose task is in a room another robot is on its way to work
// in waits where it stands until that robot is expected to have left, not at the door, and sets
// out as soon as that robot is done.
#include <gtest/gtest.h>

#include <algorithm>

#include "fleet_fixture.h"
#include "rondo/store/events.h"
#include "rondo/store/traversal_log.h"

namespace rondo::fleet::testing {
namespace {

using exec::testing::task;

int events_named(ScriptedFleet& f, const std::string& name) {
  const auto events = store::read_events(f.store());
  EXPECT_TRUE(events.ok());
  if (!events.ok()) return 0;
  return static_cast<int>(
      std::count_if(events->begin(), events->end(), [&](const store::Event& e) { return e.event == name; }));
}

// Every robot does what it is asked, 20 s a step, until `until`; never two on one node.
void work(ScriptedFleet& f, std::size_t robots, Time until) {
  while (f.clock().now() < until) {
    f.clock().run_until(f.clock().now() + seconds(20));
    for (std::size_t i = 0; i < robots; ++i) {
      ScriptedRobot& r = f.robot(i);
      if (r.driving())
        r.finish_edge(exec::EdgeOutcome::kSucceeded, seconds(20));
      else if (r.acting())
        r.finish_action(exec::ActionOutcome::kSucceeded);
    }
    f.settle();
    for (std::size_t i = 0; i < robots; ++i)
      for (std::size_t j = i + 1; j < robots; ++j)
        ASSERT_NE(f.robot(i).location(), f.robot(j).location())
            << "robots " << i << " and " << j << " at " << f.map().node(f.robot(i).location()).name;
  }
}

Task for_robot(Task t, const std::string& robot) {
  t.robot = robot;
  return t;
}

TEST(FleetTraffic, TwoRobotsWantingEachOthersRoomOneIsSentAsideAndBothAreDone) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Kitchen"}}, {}, std::nullopt, /*reserve=*/true);
  f.fleet().start();
  ASSERT_TRUE(
      f.fleet().add_task(for_robot(task("a", "Kitchen", f.at("08:00"), f.at("09:00"), minutes(2)), "r1"), "test").ok());
  ASSERT_TRUE(
      f.fleet().add_task(for_robot(task("b", "Office", f.at("08:00"), f.at("09:00"), minutes(2)), "r2"), "test").ok());
  f.settle();
  // Neither may stand in the hall in front of the other's room: both wait where they are, and the
  // deadlock is broken at once by sending one of them to a room nobody needs.
  EXPECT_GE(events_named(f, "traffic wait"), 1);
  EXPECT_EQ(events_named(f, "made way"), 1);
  ASSERT_EQ(f.reservations().resolutions().size(), 1u);
  EXPECT_EQ(f.reservations().resolutions()[0].why, traffic::MakeWay::Why::kDeadlock);
  work(f, 2, f.at("08:30"));
  EXPECT_EQ(f.fleet().book().at("a").state, TaskState::kSucceeded);
  EXPECT_EQ(f.fleet().book().at("b").state, TaskState::kSucceeded);
  EXPECT_EQ(f.reservations().unresolved(), 0u);
}

TEST(FleetTraffic, ARobotWaitingForItsWindowInTheHallMakesWayForOneThatPasses) {
  ScriptedFleet f({{"r1", "Office"}, {"r2", "Hall"}}, {}, std::nullopt, /*reserve=*/true);
  // r2's task is in the hall itself, from 08:10: it waits there for its window, parked.
  ASSERT_TRUE(
      f.fleet().add_task(for_robot(task("w", "Hall", f.at("08:10"), f.at("09:00"), minutes(2)), "r2"), "test").ok());
  f.fleet().start();
  f.settle();
  // r1, idle, goes back to its dock across the hall: r2 is asked to make way, and goes into a room
  // r1 does not need; its waiting task goes back to its queue.
  ASSERT_EQ(f.reservations().resolutions().size(), 1u);
  EXPECT_EQ(f.reservations().resolutions()[0].why, traffic::MakeWay::Why::kParked);
  const std::string aside = f.map().node(f.reservations().resolutions()[0].to).name;
  EXPECT_TRUE(aside == "Kitchen" || aside == "Lab") << aside;
  EXPECT_TRUE(f.robot(1).driving());
  EXPECT_EQ(events_named(f, "made way"), 1);
  work(f, 2, f.at("08:40"));
  EXPECT_EQ(f.map().node(f.robot(0).location()).name, "Dock");
  EXPECT_EQ(f.fleet().book().at("w").state, TaskState::kSucceeded) << "r2 came back for its own task";
}

// r1 sets out for ten minutes' work in the kitchen; then r2 gets two minutes' work there. Each has
// a room of its own for a dock.
struct KitchenTwice {
  explicit KitchenTwice(bool plan_around)
      : f({{"r1", "Office", "Office"}, {"r2", "Lab", "Lab"}}, {}, std::nullopt, /*reserve=*/true, plan_around) {
    f.fleet().start();
    EXPECT_TRUE(f.fleet()
                    .add_task(for_robot(task("a", "Kitchen", f.at("08:00"), f.at("09:00"), minutes(10)), "r1"), "test")
                    .ok());
    f.settle();
    EXPECT_TRUE(f.robot(0).driving());
    EXPECT_TRUE(f.fleet()
                    .add_task(for_robot(task("b", "Kitchen", f.at("08:00"), f.at("09:00"), minutes(2)), "r2"), "test")
                    .ok());
    f.settle();
    work(f, 2, f.at("08:45"));
    EXPECT_EQ(f.fleet().book().at("a").state, TaskState::kSucceeded);
    EXPECT_EQ(f.fleet().book().at("b").state, TaskState::kSucceeded);
  }
  ScriptedFleet f;
};

TEST(FleetTraffic, ARobotPlanningAroundAnothersStopWaitsWhereItStandsNotAtTheDoor) {
  KitchenTwice k(/*plan_around=*/true);
  EXPECT_EQ(k.f.fleet().building().deferrals.count, 1u);
  // r1 was done in 20 s, not the 10 min it was expected to take: r2 was told when r1's stop went,
  // and set out then, not at 08:10. At most it let r1 out of the kitchen.
  for (const exec::TrafficWait& w : k.f.fleet().building().traffic_waits) {
    EXPECT_EQ(w.robot, "r2");
    ASSERT_TRUE(w.end.has_value());
    EXPECT_LT(*w.end - w.start, minutes(1));
  }
  const auto events = store::read_events(k.f.store());
  ASSERT_TRUE(events.ok());
  const auto done = std::find_if(events->begin(), events->end(),
                                 [](const store::Event& e) { return e.task_id == "b" && e.event == "succeeded"; });
  ASSERT_NE(done, events->end());
  EXPECT_LT(done->time, k.f.at("08:05"));
  const auto waited = std::find_if(events->begin(), events->end(), [](const store::Event& e) {
    return e.task_id == "b" && e.reason.find("when it is free: r1 stops at Kitchen") != std::string::npos;
  });
  EXPECT_NE(waited, events->end()) << "r2 says whom it waits for";
  // Both done: neither plans a stop any more.
  EXPECT_TRUE(k.f.bookings().booked(0).empty() && k.f.bookings().booked(1).empty());
}

// r2 planned first and waits for its window; r1, which goes before it, then plans the same place
// at the same time. Both waits end together: r2, whose wait ends first, finds that r1 is due there
// and waits longer, saying for whom; it sets out when r1 is done.
TEST(FleetTraffic, ARobotWhoseWaitEndsWhenAnotherIsDueAtItsPlaceWaitsLonger) {
  ScriptedFleet f({{"r1", "Office", "Office"}, {"r2", "Lab", "Lab"}}, {}, std::nullopt, /*reserve=*/true,
                  /*plan_around=*/true);
  f.fleet().start();
  ASSERT_TRUE(
      f.fleet().add_task(for_robot(task("b", "Kitchen", f.at("08:10"), f.at("09:00"), minutes(2)), "r2"), "test").ok());
  f.settle();
  ASSERT_TRUE(
      f.fleet().add_task(for_robot(task("a", "Kitchen", f.at("08:10"), f.at("09:00"), minutes(5)), "r1"), "test").ok());
  f.settle();
  EXPECT_EQ(f.fleet().book().at("a").state, TaskState::kWaiting);
  EXPECT_EQ(f.fleet().book().at("b").state, TaskState::kWaiting);
  work(f, 2, f.at("08:40"));
  EXPECT_EQ(f.fleet().book().at("a").state, TaskState::kSucceeded);
  EXPECT_EQ(f.fleet().book().at("b").state, TaskState::kSucceeded);
  const auto events = store::read_events(f.store());
  ASSERT_TRUE(events.ok());
  const auto longer = std::find_if(events->begin(), events->end(),
                                   [](const store::Event& e) { return e.task_id == "b" && e.event == "waits longer"; });
  ASSERT_NE(longer, events->end());
  EXPECT_NE(longer->reason.find("r1 stops at Kitchen"), std::string::npos) << longer->reason;
  for (const exec::TrafficWait& w : f.fleet().building().traffic_waits) {
    ASSERT_TRUE(w.end.has_value());
    EXPECT_LT(*w.end - w.start, minutes(1)) << w.robot << " at " << w.node;
  }
}

// Its monitor does not count the wait (before, r2 overran and failed its task waiting at the door).
TEST(FleetTraffic, WithoutPlanningAroundTheSecondRobotWaitsForTheWayInstead) {
  KitchenTwice k(/*plan_around=*/false);
  EXPECT_GE(events_named(k.f, "traffic wait"), 1);
  EXPECT_EQ(k.f.fleet().building().deferrals.count, 0u);
  // The traversal log keeps the wait apart from the attempt: r2's first edge took 20 s, after a
  // wait for r1 at its start.
  const auto log = store::find_traversals(k.f.store(), {.robot = "r2"});
  ASSERT_TRUE(log.ok());
  ASSERT_FALSE(log->empty());
  const Traversal& first = log->front();
  EXPECT_EQ(first.from, "Lab");
  EXPECT_EQ(first.duration, seconds(20));
  const exec::TrafficWait& w = k.f.fleet().building().traffic_waits.front();
  ASSERT_TRUE(w.end.has_value());
  EXPECT_EQ(first.waited, *w.end - w.start);
  EXPECT_GT(first.waited, Duration{0});
}

}  // namespace
}  // namespace rondo::fleet::testing
