// Balance (issue 38): the narrowing of each unit's robots by work and battery, against its rule
// stated plainly (a property over random fleets), and on scripted robots: tasks that one robot
// would do alone, since it stands at their place, are spread across the fleet.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <map>

#include "fleet_fixture.h"
#include "rondo/fleet/balanced_allocator.h"
#include "rondo/store/events.h"

namespace rondo::fleet::testing {
namespace {

using exec::testing::task;

AllocationUnit unit(const Task* t, std::vector<std::size_t> eligible) {
  return {.tasks = {t}, .eligible = std::move(eligible)};
}

TEST(Balance, ARobotFarAboveItsShareOfWorkIsPassedOver) {
  const Task t = task("t", "Office", Time{}, Time{} + hours(2), minutes(10));
  const std::vector<Duration> loads = {Duration{0}, hours(2), minutes(20)};
  // The share: (2 h 20 min + 10 min) / 3 = 50 min; r1 is 70 min above it.
  const auto out = balanced_units({unit(&t, {0, 1, 2})}, loads, {0.9, 0.9, 0.9}, {true, true, true}, {});
  EXPECT_EQ(out[0].eligible, (std::vector<std::size_t>{0, 2}));
}

TEST(Balance, ARobotFarBelowTheBestChargeIsPassedOver) {
  const Task t = task("t", "Office", Time{}, Time{} + hours(2), minutes(10));
  const auto out = balanced_units({unit(&t, {0, 1})}, {Duration{0}, Duration{0}}, {0.95, 0.6}, {true, true}, {});
  EXPECT_EQ(out[0].eligible, (std::vector<std::size_t>{0}));
}

TEST(Balance, AUnitKeepsItsRobotsWhenNoneWouldBeLeft) {
  const Task t = task("t", "Office", Time{}, Time{} + hours(2), minutes(10));
  // Only r1 and r2 may take it, and both have far more work than r0, which is idle.
  const auto out = balanced_units({unit(&t, {1, 2}), unit(&t, {2})}, {Duration{0}, hours(3), hours(4)}, {0.9, 0.9, 0.9},
                                  {true, true, true}, {});
  EXPECT_EQ(out[0].eligible, (std::vector<std::size_t>{1, 2}));
  EXPECT_EQ(out[1].eligible, (std::vector<std::size_t>{2}));
}

// The rule, plainly: a robot stays when its load is within the margin of the able robots' mean
// load after the batch and its charge within the margin of the unit's best; when none would, all stay.
RC_GTEST_PROP(Balance, NarrowsByItsRuleAndNeverEmptiesAUnit, ()) {
  const std::size_t n = *rc::gen::inRange<std::size_t>(1, 6);
  std::vector<Duration> loads;
  std::vector<double> charges;
  std::vector<bool> able;
  for (std::size_t r = 0; r < n; ++r) {
    loads.push_back(minutes(*rc::gen::inRange(0, 600)));
    charges.push_back(*rc::gen::inRange(0, 101) / 100.0);
    able.push_back(*rc::gen::weightedElement<bool>({{4, true}, {1, false}}));
  }
  const std::vector<Task> tasks = {task("a", "Office", Time{}, Time{} + hours(9), minutes(*rc::gen::inRange(1, 120))),
                                   task("b", "Office", Time{}, Time{} + hours(9), minutes(*rc::gen::inRange(1, 120)))};
  std::vector<AllocationUnit> units;
  for (const Task& t : tasks) {
    std::vector<std::size_t> eligible;
    for (std::size_t r = 0; r < n; ++r)
      if (*rc::gen::arbitrary<bool>()) eligible.push_back(r);
    if (eligible.empty()) eligible.push_back(0);
    units.push_back(unit(&t, eligible));
  }
  const BalanceOptions o{};
  const auto out = balanced_units(units, loads, charges, able, o);
  Duration total = tasks[0].duration + tasks[1].duration;
  std::int64_t working = 0;
  for (std::size_t r = 0; r < n; ++r)
    if (able[r]) {
      total += loads[r];
      ++working;
    }
  for (std::size_t u = 0; u < units.size(); ++u) {
    const std::vector<std::size_t>& in = units[u].eligible;
    if (working == 0 || in.size() < 2) {
      RC_ASSERT(out[u].eligible == in);
      continue;
    }
    double best = 0;
    for (std::size_t r : in) best = std::max(best, charges[r]);
    std::vector<std::size_t> kept;
    for (std::size_t r : in)
      if (loads[r] <= total / working + o.work_margin && charges[r] >= best - o.battery_margin) kept.push_back(r);
    RC_ASSERT(out[u].eligible == (kept.empty() ? in : kept));
  }
}

// Light load, one robot where every task is: without balance it does them all; with it, the
// others take their share, and each such choice says whom it passed over.
TEST(Balance, SpreadsWorkThatOneRobotWouldDoAlone) {
  const auto run = [](bool balance) {
    ScriptedFleet f({{"r1", "Office"}, {"r2", "Dock"}, {"r3", "Kitchen"}}, [balance]() -> std::unique_ptr<Allocator> {
      auto greedy = std::make_unique<GreedyAllocator>();
      if (!balance) return greedy;
      return std::make_unique<BalancedAllocator>(std::move(greedy));
    });
    f.fleet().start();
    std::map<std::string, int> count;
    int passed_over = 0;
    for (int i = 0; i < 6; ++i) {
      const std::string id = "t" + std::to_string(i);
      EXPECT_TRUE(f.fleet().add_task(task(id, "Office", f.at("08:00"), f.at("18:00"), minutes(30)), "test").ok());
      f.settle();
      ++count[f.robot_of(id)];
      const auto events = store::read_events_of(f.store(), id).value();
      for (const store::Event& e : events)
        if (e.event == "allocated" && e.reason.find("for balance, passed over r1") != std::string::npos) ++passed_over;
    }
    return std::pair{count, passed_over};
  };
  const auto [alone, none] = run(false);
  EXPECT_EQ(alone.at("r1"), 6) << "it stands at the Office";
  EXPECT_EQ(none, 0);
  // r1's planned work (its running task not counted) passes the share plus 30 min at the fifth.
  const auto [spread, passed] = run(true);
  EXPECT_EQ(spread.at("r1"), 4);
  EXPECT_EQ(passed, 2);
  EXPECT_GE(spread.size(), 2u);
}

}  // namespace
}  // namespace rondo::fleet::testing
