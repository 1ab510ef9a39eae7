// What the executor keeps about the battery (src/exec/charging.h), on its own: the way home found
// closed and tried again later and later, a planned charge's stay on the charger, and the robot
// events it notes. The executor's use of it is covered by the scenario tests
// (gtest_planned_charging.cpp, gtest_battery_threshold.cpp).
#include "charging.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "plan/patchable_models.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/store/events.h"
#include "scenario.h"
#include "scripted_robot.h"

namespace rondo::exec::testing {
namespace {

const Time kT0 = from_unix_seconds(1'795'420'800);  // 2026-11-23T08:00Z, a slot start

// Charging with everything it reads: the scenario map (Dock - Hall - Office ...), a robot at Hall,
// travel from `travel_models`, and `snapshot` as the nightly snapshot.
struct Bench {
  explicit Bench(std::shared_ptr<const plan::EdgeModelView> snapshot, double reserve = 0.2)
      : snapshot_(std::move(snapshot)),
        map(scenario_map()),
        clock(kT0),
        robot(clock, map, *map.find_node("Hall")),
        db(fresh_db_path()),
        store(store::Store::open(db, {.sync_commits = false}).value()),
        book(store, clock),
        models(std::make_shared<plan::FunctionEdgeModels>(
            [](map::EdgeIndex, Time) { return plan::EdgeCrossing{.success_probability = 1, .expected_seconds = 20}; })),
        planner(map, models, {.slot_width = minutes(15)}),
        travel(map, models, planner, minutes(15)) {
    options.dock = *map.find_node("Dock");
    options.battery_planning = true;
    options.battery_reserve = reserve;
    charging = std::make_unique<Charging>(ChargingContext{.map = map,
                                                          .options = options,
                                                          .clock = clock,
                                                          .robot = robot,
                                                          .book = book,
                                                          .zone = zone,
                                                          .travel = travel,
                                                          .snapshot = *snapshot_});
    charging->read();
  }
  std::vector<std::string> robot_events(const std::string& event) const {
    std::vector<std::string> reasons;
    const std::vector<store::Event> events = store::read_events(store).value();
    for (const store::Event& e : events)
      if (e.event == event) reasons.push_back(e.reason);
    return reasons;
  }
  map::EdgeIndex edge(const std::string& id) const { return *map.find_edge(id); }

  std::shared_ptr<const plan::EdgeModelView> snapshot_;
  map::TopoMap map;
  SimClock clock;
  ScriptedRobot robot;
  std::filesystem::path db;
  store::Store store;
  TaskBook book;
  std::shared_ptr<plan::FunctionEdgeModels> models;
  plan::TravelPlanner planner;
  TravelCache travel;
  TimeZone zone = TimeZone::utc();
  ExecutorOptions options;
  std::unique_ptr<Charging> charging;
};

std::shared_ptr<const plan::EdgeModelView> always_passable() {
  return std::make_shared<plan::FunctionEdgeModels>(
      [](map::EdgeIndex, Time) { return plan::EdgeCrossing{.success_probability = 1, .expected_seconds = 20}; });
}

TEST(Charging, AClosedWayHomeIsTriedAgainTwiceAsLateEachTimeAndOpenOnceCrossed) {
  Bench b(always_passable());
  const map::EdgeIndex hall_dock = b.edge("Hall_Dock");
  EXPECT_FALSE(b.charging->way_home_closed_until());
  // A slot, then 2, 4, 8 and at most 16 slots after each failure in a row.
  for (const int slots : {1, 2, 4, 8, 16, 16}) {
    EXPECT_EQ(b.charging->retry_way_home(hall_dock), kT0 + minutes(15) * slots) << slots;
    EXPECT_EQ(b.charging->way_home_closed_until(), kT0 + minutes(15) * slots);
  }
  const std::vector<std::string> noted = b.robot_events("way home closed");
  ASSERT_EQ(noted.size(), 6u);
  EXPECT_NE(noted.back().find("Hall_Dock failed on the way to the charger (6 in a row); the next try at 12:00"),
            std::string::npos)
      << noted.back();
  // Another edge failing starts the count again.
  EXPECT_EQ(b.charging->retry_way_home(b.edge("Hall_Office")), kT0 + minutes(15));
  // A failed attempt leaves the way closed; crossing its edge opens it.
  b.charging->crossed({.edge = b.edge("Hall_Office"), .start = kT0, .outcome = EdgeOutcome::kFailed});
  EXPECT_TRUE(b.charging->way_home_closed_until());
  b.charging->crossed({.edge = b.edge("Hall_Office"), .start = kT0, .outcome = EdgeOutcome::kSucceeded});
  EXPECT_FALSE(b.charging->way_home_closed_until());
}

TEST(Charging, AClosedWayHomeWaitsForTheSlotTheSnapshotHoldsItPassable) {
  // The snapshot holds Hall_Dock blocked (p = 0.1) until 13:00, passable after.
  const auto snapshot = std::make_shared<plan::FunctionEdgeModels>([](map::EdgeIndex, Time t) {
    return plan::EdgeCrossing{.success_probability = t < kT0 + hours(5) ? 0.1 : 0.9, .expected_seconds = 20};
  });
  Bench b(snapshot);
  EXPECT_EQ(b.charging->retry_way_home(b.edge("Hall_Dock")), kT0 + hours(5));
  EXPECT_NE(b.robot_events("way home closed").back().find("when it is likely passable again (p = 0.90, learned)"),
            std::string::npos);
}

TEST(Charging, ABatteryThatCannotPayForTwoMoreAttemptsWaitsTheLongestAtOnce) {
  Bench b(always_passable());
  b.robot.battery_level = 0.2;  // at the reserve: nothing to spare for attempts on the way home
  b.charging->read();
  EXPECT_EQ(b.charging->retry_way_home(b.edge("Hall_Dock")), kT0 + minutes(15) * 16);
}

TEST(Charging, APlannedChargeStaysItsLengthOnTheChargerHoweverLongTheWayTook) {
  Bench b(always_passable());
  b.robot.battery_level = 0.5;
  b.charging->read();
  // Planned to end at 08:10 after 30 min on the charger, to 95 %.
  b.charging->start_planned(kT0 + minutes(10), minutes(30), 0.95);
  ASSERT_TRUE(b.charging->planned());
  EXPECT_TRUE(b.charging->planned_goes_on());
  // The way to the charger took until 08:25: it stays until 08:55.
  b.clock.run_until(kT0 + minutes(25));
  b.robot.move_to(*b.map.find_node("Dock"));
  b.robot.on_charger = true;
  b.charging->read();
  EXPECT_TRUE(b.charging->planned_goes_on());
  b.clock.run_until(kT0 + minutes(54));
  EXPECT_TRUE(b.charging->planned_goes_on());
  b.clock.run_until(kT0 + minutes(55));
  EXPECT_FALSE(b.charging->planned_goes_on());
  EXPECT_FALSE(b.charging->planned());
  ASSERT_EQ(b.robot_events("charged").size(), 1u);
  EXPECT_TRUE(b.robot_events("charge missed").empty());
}

TEST(Charging, APlannedChargeTheRobotNeverReachesIsMissed) {
  Bench b(always_passable());
  b.robot.battery_level = 0.5;
  b.charging->read();
  b.charging->start_planned(kT0 + minutes(10), minutes(30), 0.95);
  b.clock.run_until(kT0 + minutes(39));
  EXPECT_TRUE(b.charging->planned_goes_on());
  b.clock.run_until(kT0 + minutes(40));  // its end and its length again: given up
  EXPECT_FALSE(b.charging->planned_goes_on());
  ASSERT_EQ(b.robot_events("charge missed").size(), 1u);
  EXPECT_NE(b.robot_events("charge missed").front().find("did not reach the charger in 40m since 08:00"),
            std::string::npos)
      << b.robot_events("charge missed").front();
}

TEST(Charging, BelowTheReserveAndTheWayHomeTheRobotIsLowUntilResumed) {
  Bench b(always_passable());
  EXPECT_FALSE(b.charging->below_threshold());
  b.robot.battery_level = 0.2;  // the reserve, with nothing left for the way home from Hall
  b.charging->read();
  EXPECT_TRUE(b.charging->below_threshold());
  b.charging->enter_low();
  EXPECT_TRUE(b.charging->low());
  EXPECT_EQ(b.charging->low_since(), kT0);
  EXPECT_EQ(b.charging->figures().low_battery, 1);
  ASSERT_EQ(b.robot_events("battery low").size(), 1u);
  b.charging->resumed();
  EXPECT_FALSE(b.charging->low());
}

}  // namespace
}  // namespace rondo::exec::testing
