// The chance constraint (Problem::window_travel, docs/scheduling.md "Slack sized by risk"): every
// solver's answer passes the checker, the exact path still agrees with brute force, and a window
// travel that asks for no more than the expected travel changes nothing.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <random>

#include "brute_force.h"
#include "random_problem.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/schedule/mip_scheduler.h"
#include "rondo/schedule/try_schedule.h"

namespace rondo::schedule {
namespace {

using testing::brute_force;
using testing::random_problem;
using testing::RandomProblemOptions;

// The expected matrix stretched per entry by a factor in [1, 1 + spread] plus up to `extra_s`: a
// quantile above the mean, as a skewed travel time gives.
std::shared_ptr<const TravelOracle> stretched(const Problem& p, std::uint64_t seed, double spread, int extra_s) {
  std::mt19937_64 rng(seed);
  const std::size_t n = p.travel->location_count();
  std::vector<Duration> m(n * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      const double f = 1.0 + spread * std::uniform_real_distribution<double>(0, 1)(rng);
      const auto base = static_cast<double>(p.travel->travel(a, b, p.robot.time).count());
      const auto add = a == b ? 0 : std::uniform_int_distribution<int>(0, extra_s)(rng) * 1000;
      m[a * n + b] = Duration{static_cast<std::int64_t>(base * f) + add};
    }
  return std::make_shared<MatrixTravel>(MatrixTravel::create(n, std::move(m)).value());
}

// The same stretch made time-dependent: it grows over the first half hour, then stays (FIFO holds:
// entries only rise).
std::shared_ptr<const TravelOracle> stretched_later(const Problem& p, std::uint64_t seed) {
  const std::size_t n = p.travel->location_count();
  std::vector<Duration> before(n * n), after(n * n);
  const std::shared_ptr<const TravelOracle> top = stretched(p, seed, 0.8, 60);
  const auto& q = dynamic_cast<const MatrixTravel&>(*top);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      before[a * n + b] = p.travel->travel(a, b, p.robot.time);
      after[a * n + b] = q.at(a, b);
    }
  return std::make_shared<PiecewiseLinearTravel>(
      PiecewiseLinearTravel::create(n, {{p.robot.time + minutes(10), before}, {p.robot.time + minutes(40), after}})
          .value());
}

TEST(ChanceConstraint, DefaultAgreesWithBruteForceOnStaticAndTimeDependentQuantiles) {
  int feasible = 0, moved = 0;
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    RandomProblemOptions o;
    o.tasks = 8 + seed % 4;
    o.seed = 300 + seed;
    o.min_width_s = 120;
    o.max_width_s = 900;
    Problem p = random_problem(o);
    const auto plain = brute_force(p);
    p.window_travel = seed % 2 == 0 ? stretched(p, seed, 1.5, 240) : stretched_later(p, seed);
    ASSERT_TRUE(validate(p).ok());
    const auto truth = brute_force(p);
    const Schedule ours = DefaultScheduler{}.solve(p, NeverStop{});
    const CheckReport r = check_schedule(p, ours);
    EXPECT_TRUE(r.ok()) << "seed " << seed << ": " << r.summary();
    if (!truth.objective) {
      EXPECT_EQ(ours.status, SolveStatus::kInfeasible) << "seed " << seed;
      continue;
    }
    ++feasible;
    if (!plain.objective || *plain.objective != *truth.objective) ++moved;
    EXPECT_EQ(ours.status, SolveStatus::kOptimal) << "seed " << seed;
    EXPECT_EQ(ours.objective, *truth.objective) << "seed " << seed;
  }
  EXPECT_GE(feasible, 6);
  EXPECT_GE(moved, 1);  // the constraint binds in some of these problems
}

TEST(ChanceConstraint, TheMipRefusesIt) {
  Problem p = random_problem({.tasks = 3, .seed = 5});
  p.window_travel = p.travel;
  EXPECT_FALSE(MipScheduler::check_supported(p).ok());
}

TEST(ChanceConstraint, AWindowTravelOfAnotherSizeIsInvalid) {
  Problem p = random_problem({.tasks = 3, .seed = 5});
  p.window_travel = std::make_shared<MatrixTravel>(MatrixTravel::create(1, {Duration{0}}).value());
  const Status s = validate(p);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("window travel"), std::string::npos) << s.error().message;
}

TEST(ChanceConstraint, ATaskTheQuantileCannotReachInTimeIsDroppedWithTheQuantileTravelInItsReason) {
  // One place 10 min away on average, 25 min at the quantile; the window closes 20 min from now.
  const Time t0 = Time{} + hours(9);
  Problem p;
  p.travel = std::make_shared<MatrixTravel>(
      MatrixTravel::create(2, {Duration{0}, minutes(10), minutes(10), Duration{0}}).value());
  p.robot.time = t0;
  p.tasks.push_back({.id = "far", .release = t0, .deadline = t0 + minutes(21), .duration = minutes(1),
                     .start_location = 1, .end_location = 1});
  std::mt19937_64 rng(1);
  {
    const TryScheduleResult plain = try_schedule({.problem = p, .new_tasks = {0}}, *std::make_unique<DefaultScheduler>(),
                                                 NeverStop{}, rng);
    EXPECT_EQ(plain.outcome, TryScheduleOutcome::kAllScheduled);
  }
  p.window_travel = std::make_shared<MatrixTravel>(
      MatrixTravel::create(2, {Duration{0}, minutes(25), minutes(25), Duration{0}}).value());
  DefaultScheduler solver;
  const TryScheduleResult risky = try_schedule({.problem = p, .new_tasks = {0}}, solver, NeverStop{}, rng);
  ASSERT_EQ(risky.outcome, TryScheduleOutcome::kSomeDropped);
  ASSERT_EQ(risky.schedule.dropped.size(), 1U);
  EXPECT_NE(risky.schedule.dropped[0].reason.find("travel 25m"), std::string::npos) << risky.schedule.dropped[0].reason;
}

RC_GTEST_PROP(ChanceConstraintProperties, TheCheckerConfirmsEveryScheduleAndNoMoreThanTheMeanChangesNothing, ()) {
  RandomProblemOptions o;
  o.tasks = *rc::gen::inRange<std::size_t>(1, 9);
  o.seed = *rc::gen::arbitrary<std::uint32_t>();
  o.deliveries = *rc::gen::inRange<std::size_t>(0, 3);
  o.capacity = *rc::gen::inRange<std::int64_t>(0, 3);
  o.precedence = *rc::gen::arbitrary<bool>();
  o.min_width_s = *rc::gen::inRange<std::int64_t>(60, 900);
  o.max_width_s = o.min_width_s + *rc::gen::inRange<std::int64_t>(0, 2400);
  const Problem plain = random_problem(o);
  RC_PRE(validate(plain).ok());
  DefaultSchedulerOptions heuristic;
  heuristic.exact_max_tasks = 0;  // the anytime path alone
  const auto solve_both = [&](const Problem& p) {
    return std::pair{DefaultScheduler{}.solve(p, NeverStop{}), DefaultScheduler{heuristic}.solve(p, PollBudgetStop(3000))};
  };

  Problem risky = plain;
  const bool later = *rc::gen::arbitrary<bool>();
  risky.window_travel = later ? stretched_later(plain, o.seed) : stretched(plain, o.seed, 1.5, 300);
  const auto [exact, anytime] = solve_both(risky);
  for (const Schedule* s : {&exact, &anytime}) RC_ASSERT(check_schedule(risky, *s).ok());
  // Every schedule under the constraint is one without it: the optimum can only rise.
  const auto [exact_plain, anytime_plain] = solve_both(plain);
  if (exact.status == SolveStatus::kOptimal && exact_plain.status == SolveStatus::kOptimal)
    RC_ASSERT(exact.objective >= exact_plain.objective);
  if (exact_plain.status == SolveStatus::kInfeasible) RC_ASSERT(exact.status == SolveStatus::kInfeasible);

  // A window travel that never asks for more than the expected travel (α at or below the mean's
  // level) gives exactly the schedules without one, entry by entry.
  Problem same = plain;
  same.window_travel = plain.travel;
  const auto [exact_same, anytime_same] = solve_both(same);
  RC_ASSERT(exact_same.status == exact_plain.status);
  RC_ASSERT(exact_same.order() == exact_plain.order());
  RC_ASSERT(exact_same.objective == exact_plain.objective);
  RC_ASSERT(anytime_same.order() == anytime_plain.order());
  RC_ASSERT(anytime_same.objective == anytime_plain.objective);
}

}  // namespace
}  // namespace rondo::schedule
