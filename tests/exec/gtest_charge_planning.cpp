// Planned charging's parts (charge_planning.h): the level predicted along a schedule (worked by
// hand), charges inserted where the level would fall short, the schedule refused when no charge
// can help, and what plans missed learned per hour. A property test on random days: every answer
// passes the schedule checker and keeps the floor, or says it was refused.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <random>

#include <fmt/format.h>

#include "charge_planning.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/schedule/stop_condition.h"

namespace rondo::exec {
namespace {

using schedule::LocationIndex;
using schedule::MatrixTravel;
using schedule::Problem;
using schedule::ProblemTask;
using schedule::TryScheduleRequest;
using schedule::TryScheduleResult;

const Time kT0 = Time{} + hours(24 * 20000);

// Rates known exactly (a prior with no doubt): 0.001 per metre, 0.6 per hour moving, 0.3 per
// hour acting, nothing idle, 0.5 per hour charging.
BatteryEstimator exact_rates() {
  BatteryPrior p;
  p.mean = {.per_metre = 0.001, .moving_per_hour = 0.6, .acting_per_hour = 0.3, .idle_per_hour = 0,
            .charging_per_hour = 0.5};
  p.sd = {.per_metre = 1e-9, .moving_per_hour = 1e-9, .acting_per_hour = 1e-9, .idle_per_hour = 1e-9,
          .charging_per_hour = 1e-9};
  p.noise_sd = 1e-9;
  return BatteryEstimator(p);
}

// Dock (0) and two places: the dock to either is 6 minutes and 100 m, between them 12 minutes and
// 200 m.
Problem two_places() {
  Problem p;
  const Duration a = minutes(6), b = minutes(12);
  p.travel = std::make_shared<MatrixTravel>(
      MatrixTravel::create(3, {Duration{0}, a, a, a, Duration{0}, b, a, b, Duration{0}}).value());
  p.robot = {.location = 0, .time = kT0};
  return p;
}

ChargePlan plan_for(double level) {
  return ChargePlan{.estimator = exact_rates(), .level = level, .reserve = 0.2, .margin = 0, .dock = 0,
                    .metres = {0, 100, 100, 100, 0, 200, 100, 200, 0}};
}

schedule::Schedule solve(const Problem& p) {
  schedule::DefaultScheduler solver;
  schedule::PollBudgetStop stop(20'000);
  return solver.solve(p, stop);
}

std::function<TryScheduleResult(TryScheduleRequest&)> solver() {
  return [](TryScheduleRequest& r) {
    schedule::DefaultScheduler solver;
    schedule::PollBudgetStop stop(20'000);
    std::mt19937_64 rng(1);
    return schedule::try_schedule(r, solver, stop, rng);
  };
}

TEST(PredictLevels, FollowsTheRatesAlongTheScheduleWorkedByHand) {
  Problem p = two_places();
  p.tasks.push_back({.id = "a", .release = kT0, .deadline = kT0 + hours(8), .duration = minutes(30),
                     .start_location = 1, .end_location = 1});
  const schedule::Schedule s = solve(p);
  ASSERT_EQ(s.entries.size(), 1u);
  const LevelProfile l = predict_levels(p, s, plan_for(0.9), p.tasks.size());
  // There: 100 m (0.1) and 6 min moving (0.06); acting 30 min (0.15): 0.9 − 0.31 = 0.59.
  ASSERT_EQ(l.after.size(), 1u);
  EXPECT_NEAR(l.after[0], 0.59, 1e-6);
  // And home (another 0.16): 0.43, the lowest, above the reserve.
  EXPECT_NEAR(l.lowest, 0.43, 1e-6);
  EXPECT_FALSE(l.short_at.has_value());
  // Started at 0.6 the way home falls short; at 0.5 the task itself (0.19 + the way home's 0.16
  // must stay above 0.2 + 0.16 at its end).
  EXPECT_EQ(predict_levels(p, s, plan_for(0.6), 1).short_at, std::optional<std::size_t>(0));
  const LevelProfile low = predict_levels(p, s, plan_for(0.5), 1);
  EXPECT_EQ(low.short_at, std::optional<std::size_t>(0));
  EXPECT_NEAR(low.short_level, 0.19, 1e-6);
  EXPECT_NEAR(low.short_floor, 0.36, 1e-6);
}

TEST(PredictLevels, ALongWaitIsSpentOnTheChargerAndTheBatteryStopsWhenFull) {
  Problem p = two_places();
  p.tasks.push_back({.id = "late", .release = kT0 + hours(3), .deadline = kT0 + hours(8), .duration = minutes(30),
                     .start_location = 1, .end_location = 1});
  const schedule::Schedule s = solve(p);
  // From the dock it waits on the charger: full (not 0.5 + 3 × 0.5) when it leaves, then 0.31.
  EXPECT_NEAR(predict_levels(p, s, plan_for(0.5), 1).after.at(0), 0.69, 1e-6);
}

TEST(PlanCharges, InsertsAChargeBeforeTheTaskThatWouldFallShort) {
  Problem p = two_places();
  for (int i = 0; i < 3; ++i)
    p.tasks.push_back({.id = fmt::format("t{}", i), .release = kT0, .deadline = kT0 + hours(10),
                       .duration = minutes(40), .start_location = static_cast<LocationIndex>(1 + i % 2),
                       .end_location = static_cast<LocationIndex>(1 + i % 2)});
  TryScheduleRequest r{.problem = p, .new_tasks = {0, 1, 2}};
  const ChargePlan plan = plan_for(0.7);
  const PlannedAnswer a = plan_charges(r, &plan, solver());
  EXPECT_FALSE(a.refused);
  EXPECT_TRUE(a.for_battery.empty());
  EXPECT_EQ(a.first_charge, 3u);
  const auto& entries = a.result.schedule.entries;
  const auto charges = std::count_if(entries.begin(), entries.end(), [](const auto& e) { return e.task >= 3; });
  EXPECT_GE(charges, 1);
  EXPECT_EQ(entries.size(), 3u + static_cast<std::size_t>(charges));
  EXPECT_FALSE(predict_levels(r.problem, a.result.schedule, plan, 3).short_at.has_value());
  EXPECT_TRUE(schedule::check_schedule(r.problem, a.result.schedule).ok())
      << schedule::check_schedule(r.problem, a.result.schedule).summary();
  // Without a plan: one solve, nothing added.
  TryScheduleRequest plain{.problem = p, .new_tasks = {0, 1, 2}};
  const PlannedAnswer none = plan_charges(plain, nullptr, solver());
  EXPECT_EQ(none.result.schedule.entries.size(), 3u);
  EXPECT_EQ(plain.problem.tasks.size(), 3u);
}

TEST(PlanCharges, RefusesWhatNoChargeCanSave) {
  Problem p = two_places();
  // Must start now and drains more than there is above the reserve: no room for a charge first.
  p.tasks.push_back({.id = "now", .release = kT0, .deadline = kT0 + minutes(6) + hours(1) + minutes(1),
                     .duration = hours(1), .start_location = 1, .end_location = 1});
  TryScheduleRequest r{.problem = p, .new_tasks = {0}};
  const ChargePlan plan = plan_for(0.5);
  const PlannedAnswer a = plan_charges(r, &plan, solver());
  EXPECT_TRUE(std::none_of(a.result.schedule.entries.begin(), a.result.schedule.entries.end(),
                           [](const auto& e) { return e.task == 0; }));
  ASSERT_EQ(a.for_battery, std::vector<std::size_t>{0});
  const auto& dropped = a.result.schedule.dropped;
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].task, 0u);
}

TEST(PlanDrift, LearnsWhatPlansMissPerHour) {
  PlanDrift d;
  EXPECT_EQ(d.per_hour(), 0);
  EXPECT_NEAR(d.variance_per_hour(), 0.0025, 1e-12);  // the prior
  // Every plan says 0.05 an hour; the robot drains 0.15 an hour.
  for (int i = 0; i < 40; ++i) {
    const Time t = kT0 + hours(2 * i);
    d.planned({{t, 0.9}, {t + hours(2), 0.8}});
    d.observe(t + hours(1), 0.9 - 0.15);
  }
  EXPECT_EQ(d.observations(), 40u);
  EXPECT_NEAR(d.per_hour(), 0.1, 0.005);
  EXPECT_LT(d.variance_per_hour(), 0.0025);
  // Past the plan's last point, or too soon after its start: not used.
  d.planned({{kT0, 0.9}, {kT0 + hours(1), 0.8}});
  d.observe(kT0 + hours(2), 0.1);
  d.observe(kT0 + minutes(2), 0.1);
  EXPECT_EQ(d.observations(), 40u);
}

// Random days of 3–7 tasks on 4 places, from a random level: whatever plan_charges answers passes
// the checker, and either keeps the floor at every point or was refused (and then every task
// after the shortfall is out).
RC_GTEST_PROP(PlanChargesProperties, EveryAnswerPassesTheCheckerAndKeepsTheFloorUnlessRefused, ()) {
  const auto n = *rc::gen::inRange<std::size_t>(3, 8);
  const auto level = *rc::gen::inRange(20, 101) / 100.0;
  Problem p;
  std::vector<Duration> m(16);
  std::vector<double> metres(16);
  for (std::size_t a = 0; a < 4; ++a)
    for (std::size_t b = 0; b < 4; ++b) {
      const int s = a == b ? 0 : *rc::gen::inRange(60, 900);
      m[a * 4 + b] = seconds(s);
      metres[a * 4 + b] = s * 0.5;
    }
  p.travel = std::make_shared<MatrixTravel>(MatrixTravel::create(4, m).value());
  p.robot = {.location = 0, .time = kT0};
  for (std::size_t i = 0; i < n; ++i) {
    const Time release = kT0 + minutes(*rc::gen::inRange(0, 600));
    const Duration d = minutes(*rc::gen::inRange(5, 90));
    const LocationIndex at = *rc::gen::inRange<LocationIndex>(1, 4);
    p.tasks.push_back({.id = fmt::format("t{}", i), .release = release,
                       .deadline = release + d + hours(*rc::gen::inRange(1, 10)), .duration = d,
                       .priority = *rc::gen::inRange(0, 3), .start_location = at, .end_location = at});
  }
  std::vector<std::size_t> all;
  for (std::size_t i = 0; i < n; ++i) all.push_back(i);
  TryScheduleRequest r{.problem = p, .new_tasks = all};
  ChargePlan plan = plan_for(level);
  plan.metres = metres;
  const PlannedAnswer a = plan_charges(r, &plan, solver());
  RC_ASSERT(a.first_charge == n);
  const schedule::CheckReport report = schedule::check_schedule(r.problem, a.result.schedule);
  RC_ASSERT(report.ok());
  const LevelProfile l = predict_levels(r.problem, a.result.schedule, plan, n);
  if (!a.refused) RC_ASSERT(!l.short_at.has_value());
  // Every task is placed or dropped once.
  std::vector<int> seen(n, 0);
  for (const auto& e : a.result.schedule.entries)
    if (e.task < n) ++seen[e.task];
  for (const auto& d : a.result.schedule.dropped)
    if (d.task < n) ++seen[d.task];
  RC_ASSERT(std::all_of(seen.begin(), seen.end(), [](int k) { return k == 1; }));
}

}  // namespace
}  // namespace rondo::exec
