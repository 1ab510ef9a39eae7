// The solvers against each other and against the checker: brute force, the default scheduler and
// the MIP (both variants) agree on the optimum of random 8-12 task problems; every answer passes
// the independent checker; RapidCheck properties over random problems with deliveries.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "brute_force.h"
#include "random_problem.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/schedule/mip_scheduler.h"
#include "ticking_deadline.h"

namespace rondo::schedule {
namespace {

using testing::brute_force;
using testing::random_problem;
using testing::RandomProblemOptions;

bool complete(const Schedule& s) {
  return s.status == SolveStatus::kOptimal || s.status == SolveStatus::kFeasible;
}

TEST(Solvers, BruteForceMipAndDefaultAgreeOnRandomProblemsOf8To12Tasks) {
  int feasible = 0;
  for (std::uint64_t seed = 1; seed <= 15; ++seed) {
    RandomProblemOptions o;
    o.tasks = 8 + seed % 5;
    o.seed = seed;
    o.min_width_s = 300;
    o.max_width_s = 1500;
    const Problem p = random_problem(o);
    ASSERT_TRUE(validate(p).ok());
    const auto truth = brute_force(p);
    const NeverStop never;
    const Schedule ours = DefaultScheduler{}.solve(p, never);
    MipScheduler mip(MipOptions{false, seconds(60)});
    MipScheduler mip_ia(MipOptions{true, seconds(60)});
    const Schedule full = mip.solve(p, never);
    const Schedule fixed = mip_ia.solve(p, never);
    for (const Schedule* s : {&ours, &full, &fixed}) {
      const CheckReport r = check_schedule(p, *s);
      EXPECT_TRUE(r.ok()) << "seed " << seed << ": " << r.summary();
    }
    if (!truth.objective) {
      EXPECT_EQ(ours.status, SolveStatus::kInfeasible) << "seed " << seed;
      EXPECT_EQ(full.status, SolveStatus::kInfeasible) << "seed " << seed;
      EXPECT_EQ(fixed.status, SolveStatus::kInfeasible) << "seed " << seed;
      continue;
    }
    ++feasible;
    EXPECT_EQ(ours.status, SolveStatus::kOptimal) << "seed " << seed;
    EXPECT_EQ(full.status, SolveStatus::kOptimal) << "seed " << seed;
    EXPECT_EQ(fixed.status, SolveStatus::kOptimal) << "seed " << seed;
    EXPECT_EQ(ours.objective, *truth.objective) << "seed " << seed;
    EXPECT_EQ(full.objective, *truth.objective) << "seed " << seed;
    EXPECT_EQ(fixed.objective, *truth.objective) << "seed " << seed;
  }
  EXPECT_GE(feasible, 8);  // the generator mostly makes feasible problems
}

TEST(Solvers, DefaultMatchesBruteForceWithDeliveriesCapacityAndSameLookingItems) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    RandomProblemOptions o;
    o.tasks = 8 + seed % 3;
    o.seed = 100 + seed;
    o.deliveries = 3;
    o.capacity = seed % 2 == 0 ? 1 : 2;
    o.same_looking = seed % 3 == 0;
    o.precedence = seed % 4 == 0;
    const Problem p = random_problem(o);
    ASSERT_TRUE(validate(p).ok()) << validate(p).error().message;
    const auto truth = brute_force(p);
    const Schedule ours = DefaultScheduler{}.solve(p, NeverStop{});
    EXPECT_TRUE(check_schedule(p, ours).ok()) << check_schedule(p, ours).summary();
    if (!truth.objective) {
      EXPECT_EQ(ours.status, SolveStatus::kInfeasible) << "seed " << seed;
      continue;
    }
    EXPECT_EQ(ours.status, SolveStatus::kOptimal) << "seed " << seed;
    EXPECT_EQ(ours.objective, *truth.objective) << "seed " << seed;
  }
}

TEST(Solvers, LargeProblemsStopOnThePollBudgetWithAFeasibleSchedule) {
  RandomProblemOptions o;
  o.tasks = 120;
  o.seed = 9;
  o.horizon_s = 8 * 3600;
  o.min_width_s = 1800;
  o.max_width_s = 3 * 3600;
  const Problem p = random_problem(o);
  const PollBudgetStop stop(20000);
  const Schedule s = DefaultScheduler{}.solve(p, stop);
  ASSERT_TRUE(complete(s)) << to_string(s.status);
  EXPECT_TRUE(check_schedule(p, s).ok()) << check_schedule(p, s).summary();
}

// A problem that does not fit, under a time budget (a deadline, as the executor's background solve
// has), with the exact program out of reach: once the widest restricted program has found nothing
// the solver answers, instead of polling until the deadline with nothing left to try (which spent
// the whole budget of trySchedule's drop loop on its first attempt).
TEST(Solvers, ASolveThatFindsNoScheduleDoesNotWaitForTheDeadline) {
  Problem p;
  const Duration ten = minutes(10), zero{0};
  p.travel = std::make_shared<MatrixTravel>(MatrixTravel::create(2, {zero, ten, ten, zero}).value());
  p.location_names = {"A", "B"};
  p.robot.time = *parse_time("2026-03-02T10:00:00Z");
  for (LocationIndex at : {0U, 1U, 0U, 1U}) {
    ProblemTask t;
    t.id = "t" + std::to_string(p.tasks.size());
    t.start_location = t.end_location = at;
    t.release = p.robot.time;
    t.deadline = p.robot.time + minutes(12);
    t.duration = minutes(2);
    p.tasks.push_back(t);
  }
  constexpr std::int64_t kTicks = 10'000'000;
  const testing::TickingDeadline budget(kTicks);
  const Schedule s = DefaultScheduler{DefaultSchedulerOptions{.exact_max_tasks = 0}}.solve(p, budget);
  EXPECT_EQ(s.status, SolveStatus::kTimeout);
  EXPECT_LT(budget.readings(), kTicks / 100);
}

TEST(Solvers, TimeDependentTravelIsUsedAndChecked) {
  // Two places; the corridor is slow in the morning rush (08:00-09:00) and fast after.
  const Time t0 = Time{} + hours(8);
  auto slow = std::vector<Duration>{Duration{0}, minutes(20), minutes(20), Duration{0}};
  auto fast = std::vector<Duration>{Duration{0}, minutes(2), minutes(2), Duration{0}};
  auto travel = PiecewiseLinearTravel::create(2, {{t0, slow}, {t0 + minutes(30), slow}, {t0 + minutes(50), fast}});
  ASSERT_TRUE(travel.ok()) << travel.error().message;
  Problem p;
  p.travel = std::make_shared<PiecewiseLinearTravel>(std::move(travel).value());
  p.robot.time = t0;
  for (int i = 0; i < 3; ++i) {
    ProblemTask t;
    t.id = "t" + std::to_string(i);
    t.release = t0;
    t.deadline = t0 + hours(3);
    t.duration = minutes(5);
    t.start_location = t.end_location = static_cast<LocationIndex>(i % 2);
    p.tasks.push_back(t);
  }
  const auto truth = brute_force(p);
  const Schedule s = DefaultScheduler{}.solve(p, NeverStop{});
  ASSERT_TRUE(check_schedule(p, s).ok()) << check_schedule(p, s).summary();
  ASSERT_TRUE(truth.objective);
  EXPECT_EQ(s.objective, *truth.objective);
  EXPECT_EQ(s.status, SolveStatus::kOptimal);
}

RC_GTEST_PROP(SolverProperties, EverySolversScheduleHoldsEveryRule, ()) {
  RandomProblemOptions o;
  o.tasks = *rc::gen::inRange<std::size_t>(1, 9);
  o.seed = *rc::gen::arbitrary<std::uint32_t>();
  o.deliveries = *rc::gen::inRange<std::size_t>(0, 3);
  o.capacity = *rc::gen::inRange<std::int64_t>(0, 3);
  o.same_looking = *rc::gen::arbitrary<bool>();
  o.precedence = *rc::gen::arbitrary<bool>();
  o.min_width_s = *rc::gen::inRange<std::int64_t>(60, 900);
  o.max_width_s = o.min_width_s + *rc::gen::inRange<std::int64_t>(0, 2400);
  const Problem p = random_problem(o);
  RC_PRE(validate(p).ok());
  std::vector<Schedule> answers;
  answers.push_back(DefaultScheduler{}.solve(p, NeverStop{}));
  DefaultSchedulerOptions heuristic;
  heuristic.exact_max_tasks = 0;  // the anytime path alone
  answers.push_back(DefaultScheduler{heuristic}.solve(p, PollBudgetStop(5000)));
  if (MipScheduler::check_supported(p).ok()) {
    MipScheduler mip(MipOptions{true, seconds(30)});
    answers.push_back(mip.solve(p, NeverStop{}));
  }
  for (const Schedule& s : answers) {
    const CheckReport r = check_schedule(p, s);
    RC_ASSERT(r.ok());
    if (complete(s)) {
      // No overlap, windows, precedence and capacity are checked by the checker; restate the
      // objective here without it.
      Duration sum{0};
      for (std::size_t k = 0; k < s.entries.size(); ++k) {
        const auto& e = s.entries[k];
        RC_ASSERT(e.start >= p.tasks[e.task].release);
        RC_ASSERT(e.start <= p.tasks[e.task].latest_start());
        if (k > 0) RC_ASSERT(e.start >= s.entries[k - 1].end);
        sum += e.end - p.robot.time;
      }
      RC_ASSERT(sum == s.objective);
      RC_ASSERT(s.entries.size() == p.tasks.size());
    }
  }
  // The exact answer is never worse than any other.
  if (complete(answers[0]))
    for (const Schedule& s : answers)
      if (complete(s)) RC_ASSERT(answers[0].objective <= s.objective);
}

}  // namespace
}  // namespace rondo::schedule
