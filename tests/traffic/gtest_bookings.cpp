// The bookings of planned stops (docs/traffic.md, "Planning around each other"): whom a robot gives
// way to, the earliest time it may stop at a node, and earliest_free against a slow reference (every
// whole second from `at` on) as a property, with the answer never decreasing as `at` grows.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <vector>

#include "reservation_test_util.h"
#include "rondo/traffic/bookings.h"

namespace rondo::traffic {
namespace {

using namespace rondo::traffic::testing;

Time at_s(std::int64_t s) {
  return Time{} + seconds(s);
}

map::TopoMap counter_map() {
  return reservation_map({{"Main"}, {"Counter"}, {"Atrium", 2}},
                         {{"Main", "Counter", map::Narrow::kNone}, {"Main", "Atrium", map::Narrow::kNone}});
}

TEST(Bookings, ARobotGivesWayToThosePlannedBeforeItAndToEveryCommittedStop) {
  const map::TopoMap m = counter_map();
  Bookings b(m);
  const BookingRobot r1 = b.join("r1"), r2 = b.join("r2"), r3 = b.join("r3");
  const map::NodeIndex counter = *m.find_node("Counter");
  b.publish(r2, {{.node = counter, .from = at_s(100), .to = at_s(200)}});
  // r1 joined first: it plans as if r2's stop were not there; r3 gives way to it.
  EXPECT_EQ(b.earliest(r1, counter, at_s(150), seconds(60)), at_s(150));
  EXPECT_EQ(b.earliest(r3, counter, at_s(150), seconds(60)), at_s(200));
  EXPECT_EQ(b.earliest(r3, counter, at_s(41), seconds(60)), at_s(200));  // would still be there at 100
  EXPECT_EQ(b.earliest(r3, counter, at_s(40), seconds(60)), at_s(40));   // gone by 100
  // Committed (r2 set out): r1 gives way too.
  b.publish(r2, {{.node = counter, .from = at_s(100), .to = at_s(200), .committed = true}});
  EXPECT_EQ(b.earliest(r1, counter, at_s(150), seconds(60)), at_s(200));
  ASSERT_TRUE(b.behind(r1, counter, at_s(150), seconds(60)).has_value());
  EXPECT_EQ(b.behind(r1, counter, at_s(150), seconds(60))->robot, r2);
  EXPECT_FALSE(b.behind(r1, counter, at_s(200), seconds(60)).has_value());
  // Its own stops never hold a robot back; publishing again replaces them.
  EXPECT_EQ(b.earliest(r2, counter, at_s(150), seconds(60)), at_s(150));
  b.publish(r2, {});
  EXPECT_EQ(b.earliest(r3, counter, at_s(150), seconds(60)), at_s(150));
}

TEST(Bookings, TheRobotsWithAStopAtANodeAreToldWhenACommittedStopThereComesOrGoes) {
  const map::TopoMap m = counter_map();
  Bookings b(m);
  const BookingRobot r1 = b.join("r1"), r2 = b.join("r2"), r3 = b.join("r3");
  const map::NodeIndex counter = *m.find_node("Counter"), atrium = *m.find_node("Atrium");
  std::vector<std::pair<BookingRobot, map::NodeIndex>> told;
  for (BookingRobot r : {r1, r2, r3}) b.on_changed(r, [&told, r](map::NodeIndex n) { told.emplace_back(r, n); });
  b.publish(r3, {{.node = counter, .from = at_s(300), .to = at_s(400)}});
  b.publish(r2, {{.node = counter, .from = at_s(100), .to = at_s(200)}});  // planned: nobody is told
  EXPECT_TRUE(told.empty());
  b.publish(r2, {{.node = counter, .from = at_s(100), .to = at_s(200), .committed = true}});
  ASSERT_EQ(told.size(), 1u);  // r3 has a stop there; r1 has none
  EXPECT_EQ(told[0], std::make_pair(r3, counter));
  b.publish(r2, {{.node = counter, .from = at_s(100), .to = at_s(200), .committed = true}});  // the same
  EXPECT_EQ(told.size(), 1u);
  b.publish(r2, {{.node = atrium, .from = at_s(500), .to = at_s(600)}});  // left the counter
  ASSERT_EQ(told.size(), 2u);
  EXPECT_EQ(told[1], std::make_pair(r3, counter));
}

TEST(Bookings, ANodeWithRoomForTwoTakesASecondRobot) {
  const map::TopoMap m = counter_map();
  Bookings b(m);
  const BookingRobot r1 = b.join("r1"), r2 = b.join("r2"), r3 = b.join("r3");
  const map::NodeIndex atrium = *m.find_node("Atrium");
  b.publish(r1, {{.node = atrium, .from = at_s(0), .to = at_s(100)}});
  EXPECT_EQ(b.earliest(r3, atrium, at_s(10), seconds(10)), at_s(10));
  b.publish(r2, {{.node = atrium, .from = at_s(50), .to = at_s(150)}});
  EXPECT_EQ(b.earliest(r3, atrium, at_s(10), seconds(10)), at_s(10));   // only r1 there until 50
  EXPECT_EQ(b.earliest(r3, atrium, at_s(45), seconds(10)), at_s(100));  // both from 50 to 100
}

TEST(Bookings, AStopBetweenTwoOthersTakesTheFirstGapLongEnough) {
  const std::vector<Stop> stops{{0, at_s(10), at_s(20)}, {1, at_s(25), at_s(40)}, {2, at_s(60), at_s(70)}};
  EXPECT_EQ(earliest_free(stops, 1, at_s(12), seconds(5)), at_s(20));   // 20-25 fits 5 s
  EXPECT_EQ(earliest_free(stops, 1, at_s(12), seconds(6)), at_s(40));   // it does not fit 6
  EXPECT_EQ(earliest_free(stops, 1, at_s(12), seconds(30)), at_s(70));  // 40-60 is too short
  EXPECT_EQ(earliest_free(stops, 1, at_s(20), seconds(0)), at_s(20));   // an instant at an end
  EXPECT_EQ(earliest_free(stops, 1, at_s(10), seconds(0)), at_s(20));   // an instant at a start
}

// Stops of whole seconds in [0, 60), capacity 1-3, lengths 0-20 s.
std::vector<Stop> random_stops() {
  const auto n = *rc::gen::inRange<std::size_t>(0, 7);
  std::vector<Stop> stops;
  for (std::size_t i = 0; i < n; ++i) {
    const auto from = *rc::gen::inRange<std::int64_t>(0, 60);
    const auto length = *rc::gen::inRange<std::int64_t>(1, 20);
    stops.push_back({i, at_s(from), at_s(from + length)});
  }
  return stops;
}

// The slow reference: the first whole second from `at` at which fewer than `capacity` stops hold
// any instant of the stay (checked millisecond by millisecond at each stop's edges).
Time reference(const std::vector<Stop>& stops, int capacity, Time at, Duration length) {
  for (Time t = at;; t += seconds(1)) {
    int in = 0;
    const Time end = t + std::max(length, Duration{1});
    for (const Stop& s : stops) in += (s.from < end && t < s.to) ? 1 : 0;
    if (in < capacity) return t;
  }
}

RC_GTEST_PROP(BookingsProperty, EarliestFreeIsTheFirstFreeSecondAndNeverMovesBack, ()) {
  const std::vector<Stop> stops = random_stops();
  const int capacity = *rc::gen::inRange(1, 4);
  const Time at = at_s(*rc::gen::inRange<std::int64_t>(0, 80));
  const Duration length = seconds(*rc::gen::inRange<std::int64_t>(0, 21));
  const Time t = earliest_free(stops, capacity, at, length);
  RC_ASSERT(t == reference(stops, capacity, at, length));
  const Time later = at + seconds(*rc::gen::inRange<std::int64_t>(0, 30));
  RC_ASSERT(earliest_free(stops, capacity, later, length) >= t);
}

}  // namespace
}  // namespace rondo::traffic
