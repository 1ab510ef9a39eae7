// The fleet scheduler against its checker and a brute force: every plan on random fleets (windows,
// deliveries, capacities, same-looking items, pins, actions, `after` links, docks, speeds) passes
// the independent checker; on small cases (up to 3 robots, 7 tasks) it finds brute force's
// optimum under both objectives; a seed gives the same plan twice; one robot is today's
// scheduler's answer; a task inserted into a solved plan is planned. Budgets are poll counts,
// never seconds.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "fleet_brute_force.h"
#include "random_fleet.h"
#include "random_problem.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/schedule/fleet_checker.h"
#include "rondo/schedule/fleet_scheduler.h"

namespace rondo::schedule {
namespace {

using testing::FleetBruteForce;
using testing::random_fleet;
using testing::RandomFleetOptions;

std::vector<std::vector<std::size_t>> orders(const FleetPlan& plan) {
  std::vector<std::vector<std::size_t>> out;
  for (const auto& r : plan.routes) {
    out.emplace_back();
    for (const auto& e : r) out.back().push_back(e.task);
  }
  return out;
}

double drop_cost(const FleetProblem& p, const FleetPlan& plan) {
  double c = 0;
  for (const DroppedTask& d : plan.dropped) c += p.costs.drop_seconds * (1 + p.tasks[d.task].task.priority);
  return c;
}

RC_GTEST_PROP(FleetProperties, EveryPlanPassesTheChecker, ()) {
  RandomFleetOptions o;
  o.robots = *rc::gen::inRange<std::size_t>(1, 5);
  o.tasks = *rc::gen::inRange<std::size_t>(1, 16);
  o.seed = *rc::gen::arbitrary<std::uint32_t>();
  o.deliveries = *rc::gen::inRange<std::size_t>(0, 4);
  o.capacity = *rc::gen::inRange<std::int64_t>(0, 3);
  o.same_looking = *rc::gen::arbitrary<bool>();
  o.pins = *rc::gen::arbitrary<bool>();
  o.actions = *rc::gen::arbitrary<bool>();
  o.precedence = *rc::gen::arbitrary<bool>();
  o.docks = *rc::gen::arbitrary<bool>();
  o.speeds = *rc::gen::arbitrary<bool>();
  o.min_width_s = *rc::gen::inRange<std::int64_t>(30, 900);
  o.max_width_s = o.min_width_s + *rc::gen::inRange<std::int64_t>(0, 2400);
  o.objective = *rc::gen::arbitrary<bool>() ? FleetObjective::kSumOfEnds : FleetObjective::kVehiclesThenDistance;
  const FleetProblem p = random_fleet(o);
  RC_PRE(validate_fleet(p).ok());
  const FleetPlan plan = FleetScheduler({.seed = o.seed}).solve(p, PollBudgetStop(300));
  const FleetCheckReport r = check_fleet_plan(p, plan);
  RC_ASSERT(r.ok());
  RC_ASSERT(plan.status == SolveStatus::kFeasible);
}

struct SmallCase {
  std::size_t robots, tasks, deliveries;
  std::int64_t capacity;
  bool looks, pins, actions, docks;
};

class FleetExact : public ::testing::TestWithParam<SmallCase> {};

TEST_P(FleetExact, FindsBruteForcesOptimumUnderBothObjectives) {
  const SmallCase c = GetParam();
  for (std::uint64_t seed = 1; seed <= 6; ++seed)
    for (FleetObjective objective : {FleetObjective::kSumOfEnds, FleetObjective::kVehiclesThenDistance}) {
      const FleetProblem p = random_fleet({.robots = c.robots, .tasks = c.tasks, .seed = seed, .min_width_s = 120,
                                           .max_width_s = 1500, .deliveries = c.deliveries, .capacity = c.capacity,
                                           .same_looking = c.looks, .pins = c.pins, .actions = c.actions,
                                           .docks = c.docks, .objective = objective});
      ASSERT_TRUE(validate_fleet(p).ok());
      const auto truth = FleetBruteForce(p).solve();
      ASSERT_TRUE(truth);
      const FleetPlan plan = FleetScheduler({.seed = seed}).solve(p, PollBudgetStop(4000));
      ASSERT_TRUE(check_fleet_plan(p, plan).ok()) << check_fleet_plan(p, plan).summary();
      const std::string where = "seed " + std::to_string(seed) + (objective == FleetObjective::kSumOfEnds ? " sum" : " vrp");
      if (objective == FleetObjective::kSumOfEnds) {
        EXPECT_NEAR(plan.objective, truth->first, 1e-6) << where;
      } else {
        EXPECT_NEAR(drop_cost(p, plan), truth->first, 1e-6) << where;
        EXPECT_EQ(static_cast<double>(plan.vehicles), truth->vehicles) << where;
        EXPECT_NEAR(plan.distance, truth->rest, 1e-6) << where;
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Cases, FleetExact,
                         ::testing::Values(SmallCase{2, 6, 0, 0, false, false, false, false},
                                           SmallCase{3, 7, 0, 0, false, false, false, true},
                                           SmallCase{2, 7, 2, 1, false, false, false, false},
                                           SmallCase{3, 6, 2, 2, true, true, false, true},
                                           SmallCase{3, 7, 1, 0, false, true, true, false}));

// Rush hour: travel 50 % slower after 8:30 (FIFO: interpolated over ten minutes), robots with
// their own speed; the solver times routes by walking them, and the checker agrees.
TEST(Fleet, TimeDependentTravelPlansPassTheChecker) {
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    FleetProblem p = random_fleet({.robots = 3, .tasks = 14, .seed = seed, .deliveries = 2, .capacity = 2,
                                   .docks = true, .speeds = true});
    const auto& base = dynamic_cast<const MatrixTravel&>(*p.travel);
    const std::size_t n = base.location_count();
    std::vector<Duration> calm(n * n), rush(n * n);
    for (std::size_t a = 0; a < n; ++a)
      for (std::size_t b = 0; b < n; ++b) {
        calm[a * n + b] = base.at(a, b);
        rush[a * n + b] = base.at(a, b) * 3 / 2;
      }
    const Time t0 = Time{} + hours(8) + minutes(30);
    p.travel = std::make_shared<PiecewiseLinearTravel>(
        PiecewiseLinearTravel::create(n, {{t0, calm}, {t0 + minutes(10), rush}}).value());
    ASSERT_TRUE(validate_fleet(p).ok());
    for (auto objective : {FleetObjective::kSumOfEnds, FleetObjective::kVehiclesThenDistance}) {
      p.objective = objective;
      const FleetPlan plan = FleetScheduler({.seed = seed}).solve(p, PollBudgetStop(1500));
      EXPECT_TRUE(check_fleet_plan(p, plan).ok()) << check_fleet_plan(p, plan).summary();
    }
  }
}

TEST(Fleet, TheSameSeedGivesTheSamePlan) {
  for (auto objective : {FleetObjective::kSumOfEnds, FleetObjective::kVehiclesThenDistance}) {
    const FleetProblem p = random_fleet({.robots = 4, .tasks = 40, .seed = 11, .deliveries = 5, .capacity = 2,
                                         .pins = true, .docks = true, .objective = objective});
    const FleetPlan a = FleetScheduler({.seed = 3}).solve(p, PollBudgetStop(3000));
    const FleetPlan b = FleetScheduler({.seed = 3}).solve(p, PollBudgetStop(3000));
    EXPECT_EQ(orders(a), orders(b));
    EXPECT_EQ(a.objective, b.objective);
  }
}

TEST(Fleet, OneRobotIsTodaysSchedulersAnswer) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    const Problem one = testing::random_problem({.tasks = 12, .seed = seed, .deliveries = 2, .capacity = 1});
    FleetProblem f;
    f.travel = one.travel;
    f.robots.push_back({.name = "solo", .location = one.robot.location, .free_from = one.robot.time,
                        .capacity = one.robot.capacity});
    for (const ProblemTask& t : one.tasks) f.tasks.push_back({.task = t});
    ASSERT_TRUE(validate_fleet(f).ok());
    const Schedule s = DefaultScheduler({.seed = 1}).solve(one, PollBudgetStop(2000));
    const FleetPlan plan = FleetScheduler({.seed = 1}).solve(f, PollBudgetStop(2000));
    ASSERT_TRUE(check_fleet_plan(f, plan).ok()) << check_fleet_plan(f, plan).summary();
    if (s.status != SolveStatus::kOptimal && s.status != SolveStatus::kFeasible) continue;
    EXPECT_EQ(orders(plan).front(), s.order()) << "seed " << seed;
    EXPECT_NEAR(plan.objective, to_seconds(s.objective), 1e-6);
  }
}

TEST(Fleet, ANewTaskIsInsertedIntoASolvedPlan) {
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    FleetProblem p = random_fleet({.robots = 5, .tasks = 60, .seed = seed, .max_width_s = 7200});
    const FleetPlan plan = FleetScheduler({.seed = seed}).solve(p, PollBudgetStop(2000));
    FleetTask extra = p.tasks.front();
    extra.task.id = "new";
    extra.task.deadline = extra.task.release + hours(6);
    p.tasks.push_back(extra);
    const FleetPlan after = FleetScheduler({.seed = seed}).insert(p, plan, p.tasks.size() - 1, PollBudgetStop(200));
    ASSERT_TRUE(check_fleet_plan(p, after).ok()) << check_fleet_plan(p, after).summary();
    EXPECT_EQ(after.planned(), plan.planned() + 1);
  }
}

TEST(Fleet, ATaskNoRobotCanRunIsDroppedWithItsReason) {
  FleetProblem p = random_fleet({.robots = 2, .tasks = 3, .seed = 2, .actions = true});
  p.tasks[0].action = "fly";
  p.tasks[1].pinned_robot = 1;
  p.robots[1].free_from = p.tasks[1].task.deadline;  // too late for its pinned task
  const FleetPlan plan = FleetScheduler().solve(p, PollBudgetStop(500));
  ASSERT_TRUE(check_fleet_plan(p, plan).ok()) << check_fleet_plan(p, plan).summary();
  ASSERT_EQ(plan.dropped.size(), 2u);
  EXPECT_EQ(plan.dropped[0].reason, "no robot can run the action 'fly'");
  EXPECT_EQ(plan.dropped[1].reason, "no robot can fit it beside the other tasks");
}

TEST(FleetChecker, ReportsEveryBrokenRule) {
  FleetProblem p = random_fleet({.robots = 2, .tasks = 4, .seed = 4, .deliveries = 1, .capacity = 1});
  p.tasks[3].pinned_robot = 0;
  p.tasks[2].task.after = {3};
  // Drop on robot 0 without its pickup, the pinned task on robot 1 before its predecessor...
  auto plan = time_fleet_routes(p, {{1}, {2, 3, 0}});
  ASSERT_FALSE(plan.ok() && check_fleet_plan(p, *plan).ok());
  if (!plan) return;  // a window already broke: the plan cannot even be timed
  const FleetCheckReport r = check_fleet_plan(p, *plan);
  const std::string all = r.summary();
  EXPECT_NE(all.find("not on board"), std::string::npos) << all;
  EXPECT_NE(all.find("pinned to robot 0"), std::string::npos) << all;
  EXPECT_NE(all.find("must end first"), std::string::npos) << all;
}

}  // namespace
}  // namespace rondo::schedule
