// The executor's battery readings (src/exec/battery_watch.h): what the robot did between two
// readings becomes one interval for the estimator (metres of edges crossed, hours moving, acting,
// standing idle or on the charger), and the figures count the lowest reading and the stays on the
// charger.
#include "battery_watch.h"

#include <gtest/gtest.h>

#include "scenario.h"

namespace rondo::exec {
namespace {

const Time kT0 = from_unix_seconds(1'795'420'800);  // 2026-11-23T08:00Z

TEST(BatteryWatch, EachIntervalIsWhatTheRobotDidAndTheEstimatorLearnsItsRates) {
  const map::TopoMap map = testing::scenario_map();  // Dock -10 m- Hall -10 m- Office
  // A battery with 0.001 per metre, 0.6 per hour moving, 0.3 acting, 0.05 idle, 0.5 charging,
  // read exactly; a weak prior, so that the rates are the data's own.
  BatteryPrior weak;
  weak.sd = {.per_metre = 1, .moving_per_hour = 100, .acting_per_hour = 100, .idle_per_hour = 100,
             .charging_per_hour = 100};
  BatteryWatch watch(map, weak);
  double level = 0.4;
  Time t = kT0;
  watch.read(t, level, /*charging=*/true);
  for (int round = 0; round < 40; ++round) {
    const Duration charge = minutes(20 + round % 7), drive = seconds(25 + 5 * (round % 4)), act = minutes(3 + round % 5),
                   idle = minutes(10 + round % 3);
    t += charge;  // on the charger, then off it to Hall: one edge
    level = std::min(1.0, level + 0.5 * to_seconds(charge) / 3600);
    watch.read(t, level, true);  // just before the command
    const bool crossed = round % 5 != 0;  // every fifth attempt fails: time, no metres
    watch.edge_finished({.edge = *map.find_edge("Dock_Hall"), .start = t, .duration = drive,
                         .outcome = crossed ? EdgeOutcome::kSucceeded : EdgeOutcome::kFailed});
    t += drive;
    level -= 0.6 * to_seconds(drive) / 3600 + (crossed ? 0.001 * 10 : 0.0);
    watch.read(t, level, false);
    if (!crossed) {
      watch.edge_finished({.edge = *map.find_edge("Dock_Hall"), .start = t, .duration = drive});
      t += drive;
      level -= 0.6 * to_seconds(drive) / 3600 + 0.01;
      watch.read(t, level, false);
    }
    watch.read(t, level, false);  // before the action: nothing happened since the last reading
    watch.action_finished({.name = "work", .start = t, .duration = act});
    t += act;
    level -= 0.3 * to_seconds(act) / 3600;
    watch.read(t, level, false);
    t += idle;  // standing at Hall, then back to the dock
    level -= 0.05 * to_seconds(idle) / 3600;
    watch.read(t, level, false);
    watch.edge_finished({.edge = *map.find_edge("Hall_Dock"), .start = t, .duration = drive});
    t += drive;
    level -= 0.6 * to_seconds(drive) / 3600 + 0.01;
    watch.read(t, level, true);  // arrived: on the charger
  }
  const BatteryRates r = watch.estimator().rates();
  EXPECT_NEAR(r.per_metre, 0.001, 1e-5);
  EXPECT_NEAR(r.moving_per_hour, 0.6, 0.01);
  EXPECT_NEAR(r.acting_per_hour, 0.3, 1e-3);
  EXPECT_NEAR(r.idle_per_hour, 0.05, 1e-3);
  EXPECT_NEAR(r.charging_per_hour, 0.5, 1e-3);
  const BatteryFigures f = watch.figures();
  EXPECT_EQ(f.charges, 41);  // the first reading on the charger, and each arrival
  Duration charged{0};
  for (int round = 0; round < 40; ++round) charged += minutes(20 + round % 7);
  EXPECT_EQ(f.on_charger, charged);  // the stays only, not the drives that leave the dock
  EXPECT_LE(f.lowest, 0.4);
  EXPECT_EQ(f.empty_readings, 0u);
  EXPECT_EQ(watch.level(), level);
}

}  // namespace
}  // namespace rondo::exec
