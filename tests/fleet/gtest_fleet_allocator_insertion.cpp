// FleetSchedulerAllocator's fast way (docs/fleet.md, "The two ways to a plan"), on scripted robots
// with the thresholds lowered so that a small fleet takes it: a new task is inserted into the
// robots' own plans, read afresh at every allocation (a robot whose plan changed is seen as it is
// now, and the answer is a fresh allocator's); a unit the insertion leaves out is solved whole; the
// held travel oracle is kept within a day and made again after. Property: on random fleets the
// insertion's answers are eligible, its plan passes the checker, it holds every unit the whole
// solve holds (or the whole solve answered), and costs at most kInsertBound times the whole solve.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <algorithm>

#include "fleet_fixture.h"
#include "rondo/fleet/fleet_scheduler_allocator.h"
#include "rondo/schedule/fleet_checker.h"

namespace rondo::fleet::testing {
namespace {

using exec::testing::task;

// The insertion's objective against the whole solve's (the same bound as gtest_fleet_insert).
constexpr double kInsertBound = 1.10;

// The fast way for any fleet: a batch of up to two units, however few tasks are planned.
FleetSchedulerAllocatorOptions inserting() {
  return {.insert_units = 2, .insert_from_planned = 0};
}
FleetSchedulerAllocatorOptions solving() {
  return {.insert_units = 0};
}

std::vector<const exec::Executor*> robots_of(Fleet& fleet) {
  std::vector<const exec::Executor*> out;
  for (const auto& r : fleet.robots()) out.push_back(r.get());
  return out;
}

std::vector<std::size_t> everyone(const Fleet& fleet) {
  std::vector<std::size_t> out(fleet.robots().size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = i;
  return out;
}

// Each problem robot's route as held: its planned tasks' ids in order.
std::vector<std::vector<TaskId>> held_routes(const AllocationProblem& ap) {
  std::vector<std::vector<TaskId>> out;
  for (const auto& order : ap.orders) {
    out.emplace_back();
    for (std::size_t k : order) out.back().push_back(ap.problem.tasks[k].task.id);
  }
  return out;
}

// A morning of six tasks on the scenario map, added in one batch (solved whole: above two units).
void plan_a_morning(ScriptedFleet& f) {
  const std::vector<std::string> places{"Office", "Kitchen", "Lab", "Hall", "Office", "Lab"};
  std::vector<Task> morning;
  for (std::size_t i = 0; i < places.size(); ++i)
    morning.push_back(task("m" + std::to_string(i), places[i], f.at("09:00") + minutes(20 * static_cast<int>(i)),
                           f.at("11:00") + minutes(20 * static_cast<int>(i)), minutes(5)));
  ASSERT_TRUE(f.fleet().add_tasks(morning, "test").ok());
}

TEST(FleetAllocatorInsertion, ANewTaskIsInsertedIntoTheRobotsOwnPlans) {
  FleetSchedulerAllocator* allocator = nullptr;
  ScriptedFleet f({{"r1", "Dock"}, {"r2", "Office"}, {"r3", "Lab"}}, [&] {
    auto a = std::make_unique<FleetSchedulerAllocator>(inserting());
    allocator = a.get();
    return a;
  });
  f.fleet().start();
  plan_a_morning(f);
  EXPECT_EQ(allocator->counts().solved, 1u);
  std::vector<std::vector<TaskId>> before;
  for (const auto& r : f.fleet().robots()) before.push_back(r->activity().planned);
  ASSERT_TRUE(f.fleet().add_task(task("new", "Kitchen", f.at("09:30"), f.at("12:00"), minutes(5)), "test").ok());
  EXPECT_EQ(allocator->counts().inserted, 1u);
  const AllocationProblem& ap = *allocator->last_problem();
  // Every robot's route was its own plan, in its own order.
  for (std::size_t i = 0; i < ap.robots.size(); ++i)
    EXPECT_EQ(held_routes(ap)[i], before[ap.robots[i]]) << "robot " << i;
  const schedule::FleetCheckReport r = schedule::check_fleet_plan(ap.problem, *allocator->last_plan());
  EXPECT_TRUE(r.ok()) << r.summary();
  EXPECT_NE(f.fleet().book().at("new").robot, "");
}

// Divergence: what the robots hold is read as it is at each allocation, so a robot whose plan
// changed since the last one is seen changed, and the answer is the one a fresh allocator gives.
TEST(FleetAllocatorInsertion, ARobotWhosePlanChangedIsReadAgainAndTheAnswerIsAFreshAllocatorsOne) {
  ScriptedFleet f({{"r1", "Dock"}, {"r2", "Office"}, {"r3", "Lab"}});
  f.fleet().start();
  plan_a_morning(f);
  FleetSchedulerAllocator held(inserting());
  const Task probe = task("probe", "Hall", f.at("09:10"), f.at("10:30"), minutes(4));
  const std::vector<AllocationUnit> units{{.tasks = {&probe}, .eligible = everyone(f.fleet())}};
  held.allocate(units, robots_of(f.fleet()), f.fleet().building());
  // r2's plan changes: a task named to it.
  Task named = task("named", "Kitchen", f.at("09:00"), f.at("10:00"), minutes(10));
  named.robot = "r2";
  ASSERT_TRUE(f.fleet().add_task(named, "test").ok());
  const std::vector<Allocation> again = held.allocate(units, robots_of(f.fleet()), f.fleet().building());
  EXPECT_EQ(held.counts().inserted, 2u);
  const AllocationProblem& ap = *held.last_problem();
  const std::vector<TaskId>& r2 = f.fleet().robots()[1]->activity().planned;
  EXPECT_NE(std::find(r2.begin(), r2.end(), "named"), r2.end());
  EXPECT_EQ(held_routes(ap)[1], r2);
  FleetSchedulerAllocator fresh(inserting());
  const std::vector<Allocation> first = fresh.allocate(units, robots_of(f.fleet()), f.fleet().building());
  ASSERT_EQ(again.size(), 1u);
  EXPECT_EQ(again[0].robot, first[0].robot);
  EXPECT_EQ(again[0].why, first[0].why);
  EXPECT_EQ(held.held_travel().made(), 1u);  // its oracle kept
}

TEST(FleetAllocatorInsertion, AUnitTheInsertionLeavesOutIsSolvedWhole) {
  ScriptedFleet f({{"r1", "Dock"}, {"r2", "Office"}});
  f.fleet().start();
  plan_a_morning(f);
  FleetSchedulerAllocator a(inserting());
  // Five minutes of work at the Lab that must start now: neither robot stands there.
  const Task now = task("now", "Lab", f.at("08:00"), f.at("08:05"), minutes(5));
  const std::vector<AllocationUnit> units{{.tasks = {&now}, .eligible = everyone(f.fleet())}};
  const std::vector<Allocation> to = a.allocate(units, robots_of(f.fleet()), f.fleet().building());
  EXPECT_EQ(a.counts().inserted, 0u);
  EXPECT_EQ(a.counts().fell_back, 1u);
  EXPECT_EQ(a.counts().solved, 1u);
  // The whole solve leaves it out too: the greedy's answer, as before the fast way.
  const std::vector<Allocation> greedy = GreedyAllocator().allocate(units, robots_of(f.fleet()), f.fleet().building());
  ASSERT_EQ(to.size(), 1u);
  EXPECT_EQ(to[0].why, greedy[0].why);
}

TEST(FleetAllocatorInsertion, TheHeldTravelIsKeptWithinADayAndMadeAgainAfter) {
  ScriptedFleet f(std::vector<ScriptedFleet::RobotAt>{{"r1", "Dock"}});
  HeldTravel held;
  const auto first = held.get(f.fleet().building(), f.at("08:00"));
  EXPECT_EQ(held.get(f.fleet().building(), f.at("20:00")), first);
  EXPECT_EQ(held.made(), 1u);
  EXPECT_NE(held.get(f.fleet().building(), f.at("08:00") + hours(25)), first);
  EXPECT_EQ(held.made(), 2u);
  EXPECT_EQ(first->location_count(), f.map().node_count());
}

RC_GTEST_PROP(FleetAllocatorInsertionProperty, InsertionIsEligibleCheckedAndNearTheWholeSolve, ()) {
  const std::vector<std::string> places{"Dock", "Hall", "Office", "Kitchen", "Lab"};
  std::vector<ScriptedFleet::RobotAt> at;
  for (int r = 0; r < 3; ++r) at.push_back({"r" + std::to_string(r + 1), *rc::gen::elementOf(places)});
  ScriptedFleet f(at);
  f.fleet().start();
  const Time eight = f.at("08:00");
  std::vector<Task> first;
  for (int i = 0, n = *rc::gen::inRange(2, 9); i < n; ++i) {
    const Time release = eight + minutes(*rc::gen::inRange(0, 180));
    Task t = task("a" + std::to_string(i), *rc::gen::elementOf(places), release,
                  release + minutes(*rc::gen::inRange(15, 180)), minutes(*rc::gen::inRange(1, 9)));
    if (*rc::gen::inRange(0, 4) == 0) t.robot = at[*rc::gen::inRange<std::size_t>(0, 3)].name;
    first.push_back(t);
  }
  RC_ASSERT(f.fleet().add_tasks(first, "test").ok());
  std::vector<Task> fresh;
  for (int i = 0, n = *rc::gen::inRange(1, 3); i < n; ++i) {
    const Time release = eight + minutes(*rc::gen::inRange(0, 180));
    fresh.push_back(task("b" + std::to_string(i), *rc::gen::elementOf(places), release,
                         release + minutes(*rc::gen::inRange(10, 120)), minutes(*rc::gen::inRange(1, 9))));
  }
  std::vector<AllocationUnit> units;
  for (const Task& t : fresh) units.push_back({.tasks = {&t}, .eligible = everyone(f.fleet())});
  const auto robots = robots_of(f.fleet());
  FleetSchedulerAllocator fast(inserting()), reference(solving());
  const std::vector<Allocation> quick = fast.allocate(units, robots, f.fleet().building());
  const std::vector<Allocation> slow = reference.allocate(units, robots, f.fleet().building());
  RC_ASSERT(quick.size() == units.size());
  for (const Allocation& a : quick) RC_ASSERT(a.robot < robots.size());
  RC_ASSERT(fast.last_problem().has_value());
  const schedule::FleetCheckReport r = schedule::check_fleet_plan(fast.last_problem()->problem, *fast.last_plan());
  RC_ASSERT(r.ok());
  const bool all_slow = std::all_of(slow.begin(), slow.end(), [](const Allocation& a) { return a.fits; });
  const bool all_quick = std::all_of(quick.begin(), quick.end(), [](const Allocation& a) { return a.fits; });
  if (all_slow) RC_ASSERT(all_quick);
  RC_CLASSIFY(fast.counts().fell_back > 0, "the insertion left a unit out: solved whole");
  if (fast.counts().inserted == 1 && reference.last_plan()->dropped.empty() && fast.last_plan()->dropped.empty())
    RC_ASSERT(fast.last_plan()->objective <= kInsertBound * reference.last_plan()->objective + 1e-6);
}

}  // namespace
}  // namespace rondo::fleet::testing
