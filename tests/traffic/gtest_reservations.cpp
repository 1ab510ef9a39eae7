// The reservation rule in scenes: two robots meet head-on at a narrow corridor, three wait for each
// other in a cycle, a parked robot stands on another's only way, and grants go no further than the
// lookahead except through a narrow section, which is granted whole.
#include <gtest/gtest.h>

#include <vector>

#include "reservation_test_util.h"
#include "rondo/traffic/reservations.h"

namespace rondo::traffic {
namespace {

using namespace rondo::traffic::testing;
using map::Narrow;

std::vector<map::EdgeIndex> path(const map::TopoMap& m, std::initializer_list<const char*> ids) {
  std::vector<map::EdgeIndex> out;
  for (const char* id : ids) out.push_back(*m.find_edge(id));
  return out;
}
map::NodeIndex node(const map::TopoMap& m, const char* name) {
  return *m.find_node(name);
}

// Crosses what the robot holds, edge by edge, and asks again for the rest of its route.
std::vector<map::EdgeIndex> drive_granted(Reservations& r, RobotId robot, std::vector<map::EdgeIndex> route) {
  while (!r.granted(robot).empty()) {
    const map::EdgeIndex e = r.granted(robot).front();
    r.crossed(robot, e);
    route.erase(route.begin());
  }
  return route;
}

TEST(Reservations, HeadOnAtANarrowCorridorOneWaitsOutside) {
  // W0 - W =narrow= M =narrow= E - E0; the halls W and E hold two robots each.
  const map::TopoMap m = reservation_map({{"W0"}, {"W", 2}, {"M"}, {"E", 2}, {"E0"}}, {{"W0", "W", Narrow::kNone},
                                                                                       {"W", "M", Narrow::kSingle},
                                                                                       {"M", "E", Narrow::kSingle},
                                                                                       {"E", "E0", Narrow::kNone}});
  Reservations r(m);
  Told t1, t2;
  const RobotId a = r.join("r1", node(m, "W0"), &t1);
  const RobotId b = r.join("r2", node(m, "E0"), &t2);
  std::vector<map::EdgeIndex> ra = path(m, {"W0_W", "W_M", "M_E", "E_E0"});
  std::vector<map::EdgeIndex> rb = path(m, {"E0_E", "E_M", "M_W", "W_W0"});
  // r1 is granted the hall and the corridor whole, beyond its lookahead of 2, up to the far hall.
  EXPECT_EQ(r.request(a, node(m, "W0"), ra), 3u);
  // r2 may come into its hall (room for two) but not into the corridor r1 holds.
  EXPECT_EQ(r.request(b, node(m, "E0"), rb), 1u);
  r.crossed(b, rb[0]);
  rb.erase(rb.begin());
  EXPECT_EQ(r.request(b, node(m, "E"), rb), 0u);
  EXPECT_TRUE(r.waiting(b));
  EXPECT_EQ(r.waits_for(b), std::vector<RobotId>{a});
  EXPECT_EQ(r.passage_holders(*m.find_edge("M_E")), std::vector<RobotId>{a});
  // r1 drives through; r2 is told when r1 has left the corridor, and then gets it whole.
  ra = drive_granted(r, a, ra);
  EXPECT_GE(t2.clear, 1);
  EXPECT_EQ(r.request(b, node(m, "E"), rb), 2u);  // the corridor whole, to the far hall
  EXPECT_EQ(r.request(a, node(m, "E"), ra), 1u);  // r2 has left E0
  EXPECT_TRUE(r.resolutions().empty());
}

TEST(Reservations, ThreeInACycleTheLowestRankMakesWay) {
  // A triangle of one-robot nodes with a siding S off A.
  const map::TopoMap m = reservation_map(
      {{"A"}, {"B"}, {"C"}, {"S"}},
      {{"A", "B", Narrow::kNone}, {"B", "C", Narrow::kNone}, {"C", "A", Narrow::kNone}, {"A", "S", Narrow::kNone}});
  Reservations r(m);
  Told t1, t2, t3;
  const RobotId r1 = r.join("r1", node(m, "A"), &t1);
  const RobotId r2 = r.join("r2", node(m, "B"), &t2);
  const RobotId r3 = r.join("r3", node(m, "C"), &t3);
  r.set_rank(r1, 1);
  r.set_rank(r2, 3);
  r.set_rank(r3, 2);
  EXPECT_EQ(r.request(r1, node(m, "A"), path(m, {"A_B"})), 0u);
  EXPECT_EQ(r.request(r2, node(m, "B"), path(m, {"B_C"})), 0u);
  EXPECT_TRUE(r.resolutions().empty());  // r3 is not waiting yet: no cycle
  EXPECT_EQ(r.request(r3, node(m, "C"), path(m, {"C_A"})), 0u);
  // The cycle is closed: r1, of the lowest rank, is sent to the siding, the only node nobody needs.
  ASSERT_EQ(r.resolutions().size(), 1u);
  EXPECT_EQ(r.resolutions()[0].robot, r1);
  EXPECT_EQ(r.resolutions()[0].why, MakeWay::Why::kDeadlock);
  ASSERT_EQ(t1.make_way.size(), 1u);
  EXPECT_EQ(t1.make_way[0].route, path(m, {"A_S"}));
  EXPECT_EQ(r.granted(r1), path(m, {"A_S"}));
  EXPECT_FALSE(r.waiting(r1));
  // It drives there; r3 can go, then r2, then r1 from the siding.
  r.crossed(r1, *m.find_edge("A_S"));
  EXPECT_GE(t3.clear, 1);
  EXPECT_EQ(r.request(r3, node(m, "C"), path(m, {"C_A"})), 1u);
  r.crossed(r3, *m.find_edge("C_A"));
  EXPECT_EQ(r.request(r2, node(m, "B"), path(m, {"B_C"})), 1u);
  r.crossed(r2, *m.find_edge("B_C"));
  EXPECT_EQ(r.request(r1, node(m, "S"), path(m, {"S_A", "A_B"})), 0u);  // r3 stands at A now
  EXPECT_EQ(r.unresolved(), 0u);
}

TEST(Reservations, TheRobotThatClosesADeadlockMayBeTheOneSentAside) {
  // A - B, with a siding S off B: r2 at B, of the lower rank, closes the deadlock and is sent aside.
  const map::TopoMap m = reservation_map({{"A"}, {"B"}, {"S"}}, {{"A", "B", Narrow::kNone}, {"B", "S", Narrow::kNone}});
  Reservations r(m);
  Told t1, t2;
  const RobotId r1 = r.join("r1", node(m, "A"), &t1);
  const RobotId r2 = r.join("r2", node(m, "B"), &t2);
  r.set_rank(r1, 5);
  EXPECT_EQ(r.request(r1, node(m, "A"), path(m, {"A_B"})), 0u);
  // Nothing of its own route is held (it must not drive B_A), the way aside is, and it is told so.
  EXPECT_EQ(r.request(r2, node(m, "B"), path(m, {"B_A"})), 0u);
  EXPECT_EQ(r.granted(r2), path(m, {"B_S"}));
  ASSERT_EQ(t2.make_way.size(), 1u);
  EXPECT_EQ(t2.make_way[0].for_robots, std::vector<RobotId>{r1});
}

TEST(Reservations, ADeadlockWithNowhereToGoIsCountedUnresolved) {
  const map::TopoMap m = reservation_map({{"A"}, {"B"}}, {{"A", "B", Narrow::kNone}});
  Reservations r(m);
  const RobotId a = r.join("r1", node(m, "A"), nullptr);
  const RobotId b = r.join("r2", node(m, "B"), nullptr);
  EXPECT_EQ(r.request(a, node(m, "A"), path(m, {"A_B"})), 0u);
  EXPECT_EQ(r.request(b, node(m, "B"), path(m, {"B_A"})), 0u);
  EXPECT_TRUE(r.resolutions().empty());
  EXPECT_EQ(r.unresolved(), 1u);
}

// A - B - C, with a recess P off B.
map::TopoMap recess_map() {
  return reservation_map({{"A"}, {"B"}, {"C"}, {"P"}},
                         {{"A", "B", Narrow::kNone}, {"B", "C", Narrow::kNone}, {"B", "P", Narrow::kNone}});
}

TEST(Reservations, AParkedRobotOnTheOnlyWayIsAskedToMakeWay) {
  const map::TopoMap m = recess_map();
  Reservations r(m);
  Told t1, t2;
  const RobotId mover = r.join("r1", node(m, "A"), &t1);
  const RobotId parked = r.join("r2", node(m, "B"), &t2);
  // At work at B (not parked): r1 waits, and nobody is asked to move.
  EXPECT_EQ(r.request(mover, node(m, "A"), path(m, {"A_B", "B_C"})), 0u);
  EXPECT_TRUE(t2.make_way.empty());
  // Its work done, r2 parks where it is: it is asked at once to clear the way, into the recess.
  r.set_parked(parked, true);
  ASSERT_EQ(t2.make_way.size(), 1u);
  EXPECT_EQ(t2.make_way[0].why, MakeWay::Why::kParked);
  EXPECT_EQ(t2.make_way[0].route, path(m, {"B_P"}));
  EXPECT_EQ(t2.make_way[0].for_robots, std::vector<RobotId>{mover});
  r.crossed(parked, *m.find_edge("B_P"));
  EXPECT_GE(t1.clear, 1);
  EXPECT_EQ(r.request(mover, node(m, "A"), path(m, {"A_B", "B_C"})), 2u);
}

// Sent aside, the robot arrives and stops there before the robot it made way for has asked again
// (its call comes later): it does not take the way back first (else the two would make way for
// each other in turn), but once that robot has gone by.
TEST(Reservations, ARobotSentAsideKeepsYieldingAfterItStopsThere) {
  const map::TopoMap m = recess_map();
  Reservations r(m);
  Told t1, t2;
  const RobotId mover = r.join("r1", node(m, "A"), &t1);
  const RobotId parked = r.join("r2", node(m, "B"), &t2);
  r.set_parked(parked, true);
  EXPECT_EQ(r.request(mover, node(m, "A"), path(m, {"A_B", "B_C"})), 0u);
  ASSERT_EQ(t2.make_way.size(), 1u);
  r.crossed(parked, *m.find_edge("B_P"));
  r.stop(parked, node(m, "P"));
  // r2 wants to go back to B at once: it waits for r1, which still waits.
  EXPECT_EQ(r.request(parked, node(m, "P"), path(m, {"P_B"})), 0u);
  EXPECT_EQ(r.request(mover, node(m, "A"), path(m, {"A_B", "B_C"})), 2u);
  r.crossed(mover, *m.find_edge("A_B"));
  r.crossed(mover, *m.find_edge("B_C"));
  r.stop(mover, node(m, "C"));
  EXPECT_EQ(r.request(parked, node(m, "P"), path(m, {"P_B"})), 1u);
}

TEST(Reservations, GrantsGoNoFurtherThanTheLookaheadButANarrowSectionIsWhole) {
  const map::TopoMap m = reservation_map({{"A"}, {"B"}, {"C"}, {"D"}, {"E"}, {"F"}}, {{"A", "B", Narrow::kNone},
                                                                                      {"B", "C", Narrow::kNone},
                                                                                      {"C", "D", Narrow::kOneWay},
                                                                                      {"D", "E", Narrow::kOneWay},
                                                                                      {"E", "F", Narrow::kNone}});
  Reservations r(m, {.lookahead = 2});
  const RobotId a = r.join("r1", node(m, "A"), nullptr);
  std::vector<map::EdgeIndex> route = path(m, {"A_B", "B_C", "C_D", "D_E", "E_F"});
  EXPECT_EQ(r.request(a, node(m, "A"), route), 2u);
  EXPECT_TRUE(r.holders(node(m, "D")).empty());
  r.crossed(a, route[0]);
  route.erase(route.begin());
  // From B: B_C, then the one-way section C-D-E whole.
  EXPECT_EQ(r.request(a, node(m, "B"), route), 3u);
  EXPECT_EQ(r.holders(node(m, "E")), std::vector<RobotId>{a});
  EXPECT_TRUE(r.holders(node(m, "F")).empty());
  // A robot the other way may not enter the section; one following may, once the nodes are free.
  const RobotId b = r.join("r2", node(m, "F"), nullptr);
  EXPECT_EQ(r.request(b, node(m, "F"), path(m, {"F_E", "E_D"})), 0u);
  // A new route drops what the old held off it.
  EXPECT_EQ(r.request(a, node(m, "B"), path(m, {"B_A"})), 1u);
  EXPECT_TRUE(r.holders(node(m, "C")).empty());
  EXPECT_TRUE(r.passage_holders(*m.find_edge("C_D")).empty());
}

TEST(Reservations, ADeadEndIsEnteredWithTheNodeInFrontOfIt) {
  // A - B - C, with a counter K off B (a dead end): r2 is at the counter.
  const map::TopoMap m =
      reservation_map({{"A"}, {"B", 2}, {"C"}, {"K"}},
                      {{"A", "B", Narrow::kNone}, {"B", "C", Narrow::kNone}, {"B", "K", Narrow::kNone}});
  Reservations r(m);
  const RobotId a = r.join("r1", node(m, "A"), nullptr);
  const RobotId k = r.join("r2", node(m, "K"), nullptr);
  // r1 is not let into B to queue for the counter (B would fill, and r2 could not get out) ...
  EXPECT_EQ(r.request(a, node(m, "A"), path(m, {"A_B", "B_K"})), 0u);
  EXPECT_EQ(r.waits_for(a), std::vector<RobotId>{k});
  // ... but passes B on its way to C.
  EXPECT_EQ(r.request(a, node(m, "A"), path(m, {"A_B", "B_C"})), 2u);
  r.stop(a, node(m, "A"));
  // r2 leaves the counter: r1 gets B and the counter together.
  r.stop(k, node(m, "C"));
  EXPECT_EQ(r.request(a, node(m, "A"), path(m, {"A_B", "B_K"})), 2u);
}

TEST(Reservations, ARobotFoundElsewhereHoldsWhereItIs) {
  const map::TopoMap m = reservation_map({{"A"}, {"B"}, {"C"}}, {{"A", "B", Narrow::kNone}, {"B", "C", Narrow::kNone}});
  Reservations r(m);
  const RobotId a = r.join("r1", node(m, "A"), nullptr);
  EXPECT_EQ(r.request(a, node(m, "A"), path(m, {"A_B"})), 1u);
  r.stop(a, node(m, "C"));  // carried to C
  EXPECT_TRUE(r.holders(node(m, "A")).empty());
  EXPECT_TRUE(r.holders(node(m, "B")).empty());
  EXPECT_EQ(r.holders(node(m, "C")), std::vector<RobotId>{a});
  EXPECT_THROW(r.request(a, node(m, "C"), path(m, {"A_B"})), std::invalid_argument);
  r.leave(a);
  EXPECT_TRUE(r.holders(node(m, "C")).empty());
}

}  // namespace
}  // namespace rondo::traffic
