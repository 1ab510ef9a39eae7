// Insertion into held routes (FleetScheduler::insert with orders): the fleet allocator's fast way
// (docs/fleet.md, "The two ways to a plan"). A held plan takes a new unit (a task, or a delivery's
// pickup and drop) and stays feasible with every held task on its robot; a held route that breaks
// a rule is held without the tasks that break it; property: on random small fleets the insertion
// passes the checker, keeps every held task planned, and costs at most kInsertBound times the
// whole solve of the same problem (the slow reference) where it holds the unit; where it does not,
// the allocator takes the reference's answer (counted). Budgets are poll counts.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>

#include "random_fleet.h"
#include "rondo/schedule/fleet_checker.h"
#include "rondo/schedule/fleet_scheduler.h"

namespace rondo::schedule {
namespace {

using testing::random_fleet;
using testing::RandomFleetOptions;

// The insertion's objective against the whole solve's, where both hold every task they can:
// docs/fleet.md gives the measured spread.
constexpr double kInsertBound = 1.10;

std::vector<std::vector<std::size_t>> orders_of(const FleetPlan& plan) {
  std::vector<std::vector<std::size_t>> out;
  for (const auto& r : plan.routes) {
    out.emplace_back();
    for (const auto& e : r) out.back().push_back(e.task);
  }
  return out;
}

bool planned(const FleetPlan& plan, std::size_t task) {
  return std::none_of(plan.dropped.begin(), plan.dropped.end(), [&](const DroppedTask& d) { return d.task == task; });
}

// The plan held before `fresh` came: the same problem with those tasks given to no robot.
FleetPlan held_plan(const FleetProblem& p, const std::vector<std::size_t>& fresh, std::uint64_t seed) {
  FleetProblem before = p;
  for (std::size_t t : fresh) {
    before.tasks[t].action = "not yet here";
    before.tasks[t].pinned_robot.reset();
  }
  return FleetScheduler({.seed = seed}).solve(before, PollBudgetStop(1000));
}

// The new unit: task 0 (with its drop, task 1, when it is a pickup), its pin and action cleared.
std::vector<std::size_t> new_unit(FleetProblem& p) {
  std::vector<std::size_t> fresh{0};
  if (p.tasks[0].task.transfer) fresh.push_back(1);
  for (std::size_t t : fresh) p.tasks[t].pinned_robot.reset();
  return fresh;
}

TEST(FleetInsert, AHeldPlanTakesANewUnitAndStaysFeasible) {
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    FleetProblem p = random_fleet({.robots = 5,
                                   .tasks = 60,
                                   .seed = seed,
                                   .max_width_s = 5400,
                                   .deliveries = 3,
                                   .capacity = 1,
                                   .pins = true,
                                   .docks = true});
    const std::vector<std::size_t> fresh = new_unit(p);
    const FleetPlan held = held_plan(p, fresh, seed);
    const FleetPlan after = FleetScheduler({.seed = seed}).insert(p, orders_of(held), fresh, PollBudgetStop(100));
    const FleetCheckReport r = check_fleet_plan(p, after);
    ASSERT_TRUE(r.ok()) << "seed " << seed << ": " << r.summary();  // windows, capacity, pins, dock
    for (std::size_t t : fresh) EXPECT_TRUE(planned(after, t)) << "seed " << seed;
    for (std::size_t t = 0; t < p.tasks.size(); ++t) {
      if (planned(held, t)) {
        EXPECT_TRUE(planned(after, t)) << "seed " << seed << " task " << t;
      }
    }
  }
}

TEST(FleetInsert, AHeldRouteThatBreaksAWindowIsHeldWithoutTheTaskThatBreaksIt) {
  FleetProblem p = random_fleet({.robots = 2, .tasks = 8, .seed = 3, .max_width_s = 3600});
  const FleetPlan held = FleetScheduler({.seed = 3}).solve(p, PollBudgetStop(500));
  ASSERT_TRUE(check_fleet_plan(p, held).ok());
  std::vector<std::vector<std::size_t>> orders = orders_of(held);
  ASSERT_FALSE(orders[0].empty());
  // Robot 0's first task now closes before the robot could be there.
  const std::size_t broken = orders[0].front();
  p.tasks[broken].task.release = p.robots[0].free_from - hours(2);
  p.tasks[broken].task.deadline = p.robots[0].free_from - hours(1);
  p.tasks[broken].task.duration = Duration{0};
  const FleetPlan after = FleetScheduler({.seed = 3}).insert(p, orders, {}, PollBudgetStop(10));
  const FleetCheckReport r = check_fleet_plan(p, after);
  ASSERT_TRUE(r.ok()) << r.summary();
  EXPECT_FALSE(planned(after, broken));
  for (std::size_t t = 0; t < p.tasks.size(); ++t) {
    if (t != broken) {
      EXPECT_TRUE(planned(after, t)) << "task " << t;
    }
  }
}

RC_GTEST_PROP(FleetInsertProperty, InsertionIsCheckedKeepsTheHeldAndIsNearTheWholeSolve, ()) {
  RandomFleetOptions o;
  o.robots = *rc::gen::inRange<std::size_t>(2, 5);
  o.tasks = *rc::gen::inRange<std::size_t>(4, 16);
  o.seed = *rc::gen::inRange<std::uint64_t>(1, 100000);
  o.deliveries = *rc::gen::inRange<std::size_t>(0, 3);
  o.capacity = *rc::gen::inRange<std::int64_t>(0, 3);
  o.pins = *rc::gen::arbitrary<bool>();
  o.actions = *rc::gen::arbitrary<bool>();
  o.docks = *rc::gen::arbitrary<bool>();
  o.speeds = *rc::gen::arbitrary<bool>();
  FleetProblem p = random_fleet(o);
  RC_PRE(validate_fleet(p).ok());
  const std::vector<std::size_t> fresh = new_unit(p);
  RC_PRE(validate_fleet(p).ok());
  const FleetPlan held = held_plan(p, fresh, o.seed);
  const FleetPlan inserted = FleetScheduler({.seed = o.seed}).insert(p, orders_of(held), fresh, PollBudgetStop(100));
  const FleetCheckReport r = check_fleet_plan(p, inserted);
  RC_ASSERT(r.ok());  // each task on a robot that may run it, pins, windows, capacity, dock
  for (std::size_t t = 0; t < p.tasks.size(); ++t)
    if (planned(held, t)) RC_ASSERT(planned(inserted, t));
  const FleetPlan reference = FleetScheduler({.seed = o.seed}).solve(p, PollBudgetStop(1000));
  const bool holds = std::all_of(fresh.begin(), fresh.end(), [&](std::size_t t) { return planned(inserted, t); });
  const bool could = std::all_of(fresh.begin(), fresh.end(), [&](std::size_t t) { return planned(reference, t); });
  RC_CLASSIFY(!holds && could, "left out where the whole solve holds it: the allocator takes the whole solve");
  if (!holds) return;
  const double ratio = inserted.objective / std::max(1e-9, reference.objective);
  RC_CLASSIFY(ratio > 1 + 1e-9, "above the whole solve");
  RC_CLASSIFY(ratio > 1.05, "more than 5 % above");
  RC_CLASSIFY(ratio < 1 - 1e-9, "below the whole solve");
  RC_ASSERT(inserted.objective <= kInsertBound * reference.objective + 1e-6);
}

}  // namespace
}  // namespace rondo::schedule
