// Robots in each other's way (sim::Traffic with SimRobots on one clock), on small maps with exact
// timing: an edge of 10 m takes 10 s.
#include "rondo/sim/traffic.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "rondo/exec/clock.h"
#include "rondo/sim/sim_robot.h"
#include "traffic_test_util.h"

namespace rondo::sim {
namespace {

using namespace rondo::sim::testing;
using map::Narrow;

const Time kT0 = parse_time("2026-11-23T10:00:00Z").value();

// Robots named r1, r2... on one map, one world, one clock and one traffic.
struct Building {
  map::TopoMap m;
  SimWorld world;
  exec::SimClock clock{kT0};
  Traffic traffic;
  std::vector<std::unique_ptr<Attempts>> heard;
  std::vector<std::unique_ptr<SimRobot>> robots;

  Building(map::TopoMap plan, std::vector<const char*> starts, std::vector<const char*> closed = {},
           TrafficOptions options = {})
      : m(std::move(plan)), world(exact_traffic_world(m, edges(closed))), traffic(m, options) {
    for (const char* start : starts) {
      const std::string name = "r" + std::to_string(robots.size() + 1);
      robots.push_back(std::make_unique<SimRobot>(clock, m, world,
                                                  SimRobotOptions{.start = node(m, start),
                                                                  .dock = node(m, start),
                                                                  .seed = robots.size() + 1,
                                                                  .name = name,
                                                                  .traffic = &traffic}));
      heard.push_back(std::make_unique<Attempts>());
      robots.back()->set_listener(heard.back().get());
    }
  }
  std::vector<map::EdgeIndex> edges(const std::vector<const char*>& ids) const {
    std::vector<map::EdgeIndex> out;
    for (const char* id : ids) out.push_back(edge(m, id));
    return out;
  }
  // Robot i (from 1) starts edge `id` at kT0 + `at`.
  void traverse_at(std::size_t i, const char* id, Duration at) {
    clock.schedule_at(kT0 + at, [this, i, id] { robots[i - 1]->traverse(edge(m, id)); });
  }
  const exec::EdgeAttempt& only_attempt(std::size_t i) const {
    EXPECT_EQ(heard[i - 1]->edges.size(), 1u) << "r" << i;
    return heard[i - 1]->edges.at(0);
  }
};

TEST(Traffic, HeadOnInASingleCorridorOneWaitsTheOtherPasses) {
  Building b(traffic_map({{"W", 0, 0, 2}, {"E", 20, 0, 2}}, {{"W", "E", Narrow::kSingle}}), {"W", "E"});
  b.traverse_at(1, "W_E", seconds(0));
  b.traverse_at(2, "E_W", seconds(5));  // r1 is in the corridor: r2 waits at E
  b.clock.run_until(kT0 + minutes(5));
  EXPECT_TRUE(b.only_attempt(1).succeeded());
  EXPECT_EQ(b.only_attempt(1).duration, seconds(20));
  const exec::EdgeAttempt& second = b.only_attempt(2);
  EXPECT_TRUE(second.succeeded());
  EXPECT_EQ(second.start, kT0 + seconds(5));
  EXPECT_EQ(second.duration, seconds(15 + 20));  // held until r1 was out, then its 20 s
  ASSERT_EQ(b.traffic.hold_ups().size(), 1u);
  const HoldUp& h = b.traffic.hold_ups()[0];
  EXPECT_EQ(h.robot, "r2");
  EXPECT_EQ(h.node, "E");
  EXPECT_EQ(h.blocker.robot, "r1");
  EXPECT_EQ(h.blocker.place, "on W_E (narrow: single)");
  EXPECT_EQ(h.held(), seconds(15));
  EXPECT_EQ(h.how, HoldUp::End::kPassed);
  EXPECT_TRUE(b.traffic.collisions().empty());
  EXPECT_EQ(b.robots[0]->location(), node(b.m, "E"));
  EXPECT_EQ(b.robots[1]->location(), node(b.m, "W"));
}

TEST(Traffic, OneWayLetsFollowersThroughAndHoldsTheOtherDirection) {
  Building b(traffic_map({{"W", 0, 0, 2}, {"E", 20, 0, 3}}, {{"W", "E", Narrow::kOneWay}}), {"W", "W", "E"});
  b.traverse_at(1, "W_E", seconds(0));
  b.traverse_at(2, "W_E", seconds(2));  // behind r1, the same way: goes at once
  b.traverse_at(3, "E_W", seconds(4));  // against them: waits until both are out
  b.clock.run_until(kT0 + minutes(5));
  EXPECT_EQ(b.only_attempt(2).duration, seconds(20));
  EXPECT_EQ(b.only_attempt(3).duration, seconds(18 + 20));
  ASSERT_EQ(b.traffic.hold_ups().size(), 1u);
  EXPECT_EQ(b.traffic.hold_ups()[0].robot, "r3");
  EXPECT_EQ(b.traffic.hold_ups()[0].blocker.place, "on W_E (narrow: one_way)");
  EXPECT_EQ(b.traffic.hold_ups()[0].held(), seconds(18));
  EXPECT_TRUE(b.traffic.collisions().empty());
}

TEST(Traffic, ANodeOfCapacityTwoLetsTwoInAndHoldsTheThird) {
  Building b(traffic_map({{"A", 0, 0}, {"B", 20, 0}, {"C", 10, 10}, {"Hub", 10, 0, 2}},
                         {{"A", "Hub", Narrow::kNone}, {"B", "Hub", Narrow::kNone}, {"C", "Hub", Narrow::kNone}}),
             {"A", "B", "C"});
  b.traverse_at(1, "A_Hub", seconds(0));
  b.traverse_at(2, "B_Hub", seconds(0));
  b.traverse_at(3, "C_Hub", seconds(0));  // both places are claimed by robots on their way
  b.traverse_at(1, "Hub_A", seconds(15));
  b.clock.run_until(kT0 + minutes(5));
  EXPECT_EQ(b.only_attempt(2).duration, seconds(10));
  EXPECT_EQ(b.only_attempt(3).duration, seconds(15 + 10));  // in once r1 left the hub
  ASSERT_EQ(b.traffic.hold_ups().size(), 1u);
  EXPECT_EQ(b.traffic.hold_ups()[0].blocker.text(), "held up by r1 on its way to Hub");
  EXPECT_TRUE(b.traffic.collisions().empty());
  EXPECT_EQ(b.traffic.standing(node(b.m, "Hub")), 2);
}

TEST(Traffic, AHeldRobotFailsAfterTheHoldTimeoutNamingTheBlocker) {
  Building b(traffic_map({{"W", 0, 0}, {"M", 10, 0}}, {{"W", "M", Narrow::kNone}}), {"W", "M"});
  b.traverse_at(1, "W_M", seconds(0));  // r2 stands at M, and stays
  b.clock.run_until(kT0 + minutes(5));
  const exec::EdgeAttempt& a = b.only_attempt(1);
  EXPECT_EQ(a.outcome, exec::EdgeOutcome::kFailed);
  EXPECT_EQ(a.message, "held up by r2 at M");
  EXPECT_EQ(a.duration, seconds(60));  // the default hold_timeout
  EXPECT_EQ(b.robots[0]->location(), node(b.m, "W"));
  ASSERT_EQ(b.traffic.hold_ups().size(), 1u);
  EXPECT_EQ(b.traffic.hold_ups()[0].how, HoldUp::End::kTimedOut);
  EXPECT_TRUE(b.traffic.collisions().empty());
}

TEST(Traffic, TheHoldTimeoutIsTheWorldsOption) {
  Building b(traffic_map({{"W", 0, 0}, {"M", 10, 0}}, {{"W", "M", Narrow::kNone}}), {"W", "M"}, {},
             {.hold_timeout = seconds(25)});
  b.traverse_at(1, "W_M", seconds(0));
  b.clock.run_until(kT0 + minutes(5));
  EXPECT_EQ(b.only_attempt(1).duration, seconds(25));
}

TEST(Traffic, CancellingAHeldRobotEndsItsHold) {
  Building b(traffic_map({{"W", 0, 0}, {"M", 10, 0}}, {{"W", "M", Narrow::kNone}}), {"W", "M"});
  b.traverse_at(1, "W_M", seconds(0));
  b.clock.schedule_at(kT0 + seconds(10), [&] { b.robots[0]->cancel(); });
  b.clock.run_until(kT0 + minutes(5));
  EXPECT_EQ(b.only_attempt(1).outcome, exec::EdgeOutcome::kCancelled);
  EXPECT_EQ(b.only_attempt(1).duration, seconds(10));
  ASSERT_EQ(b.traffic.hold_ups().size(), 1u);
  EXPECT_EQ(b.traffic.hold_ups()[0].how, HoldUp::End::kStopped);
  EXPECT_FALSE(b.robots[0]->busy());
}

TEST(Traffic, AFailedAttemptBackOnATakenNodeIsACollision) {
  // r1 leaves A for B and fails after 5 s; meanwhile r2 came from C into A, which was free.
  Building b(
      traffic_map({{"A", 0, 0}, {"B", 0, 10}, {"C", 3, 0}}, {{"A", "B", Narrow::kNone}, {"C", "A", Narrow::kNone}}),
      {"A", "C"}, {"A_B"});
  b.traverse_at(1, "A_B", seconds(0));
  b.traverse_at(2, "C_A", seconds(1));
  b.clock.run_until(kT0 + minutes(5));
  EXPECT_EQ(b.only_attempt(1).outcome, exec::EdgeOutcome::kFailed);
  EXPECT_TRUE(b.only_attempt(2).succeeded());
  ASSERT_EQ(b.traffic.collisions().size(), 1u);
  const Collision& c = b.traffic.collisions()[0];
  EXPECT_EQ(c.kind, Collision::Kind::kNode);
  EXPECT_EQ(c.place, "A");
  EXPECT_EQ(c.at, kT0 + seconds(5));
  EXPECT_EQ(c.robots, (std::vector<std::string>{"r1", "r2"}));
  EXPECT_EQ(b.traffic.standing(node(b.m, "A")), 2);
}

TEST(Traffic, RobotsPlacedBeyondANodesCapacityCollideAtTheStart) {
  Building b(traffic_map({{"A", 0, 0}, {"B", 10, 0}}, {{"A", "B", Narrow::kNone}}), {"A", "A"});
  ASSERT_EQ(b.traffic.collisions().size(), 1u);
  EXPECT_EQ(b.traffic.collisions()[0].at, kT0);
  EXPECT_EQ(b.traffic.collisions()[0].robots, (std::vector<std::string>{"r2", "r1"}));
}

TEST(Traffic, ALoneRobotDrivesAsWithoutTraffic) {
  const map::TopoMap m = traffic_map({{"A", 0, 0}, {"B", 10, 0}, {"C", 10, 10}},
                                     {{"A", "B", Narrow::kSingle}, {"B", "C", Narrow::kOneWay}});
  const auto drive = [&](Traffic* traffic) {
    SimWorld world = exact_traffic_world(m, {}, 0.3, 0.4);
    exec::SimClock clock(kT0);
    Attempts heard;
    SimRobot robot(clock, m, world, {.start = node(m, "A"), .seed = 9, .traffic = traffic});
    robot.set_listener(&heard);
    for (int i = 0; i < 20; ++i) {
      const map::NodeIndex at = robot.location();
      robot.traverse(m.out_edges(at)[static_cast<std::size_t>(i) % m.out_edges(at).size()]);
      clock.run_until(clock.now() + minutes(2));
    }
    std::vector<std::tuple<map::EdgeIndex, Time, Duration, exec::EdgeOutcome>> out;
    for (const exec::EdgeAttempt& a : heard.edges) out.emplace_back(a.edge, a.start, a.duration, a.outcome);
    return out;
  };
  Traffic traffic(m);
  EXPECT_EQ(drive(&traffic), drive(nullptr));
  EXPECT_TRUE(traffic.hold_ups().empty());
  EXPECT_TRUE(traffic.collisions().empty());
}

}  // namespace
}  // namespace rondo::sim
