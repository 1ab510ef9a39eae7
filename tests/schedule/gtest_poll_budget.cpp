// The default scheduler under a poll budget (PollBudgetStop) is a function of its input alone: the
// executor calls it that way so that a run replays byte for byte. Identical problems and budgets
// give identical schedules, whatever ran before in the process and wherever the heap put things;
// a larger budget never gives a worse schedule.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "random_problem.h"
#include "robot_day.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"

namespace rondo::schedule {
namespace {

using testing::random_problem;
using testing::RandomProblemOptions;

bool complete(const Schedule& s) { return s.status == SolveStatus::kOptimal || s.status == SolveStatus::kFeasible; }

// Every field the executor could read, compared exactly.
std::string difference(const Schedule& a, const Schedule& b) {
  if (a.status != b.status) return "status";
  if (a.objective != b.objective) return "objective";
  if (a.lower_bound != b.lower_bound) return "lower bound";
  if (a.return_arrival != b.return_arrival) return "return arrival";
  if (a.entries.size() != b.entries.size()) return "entry count";
  for (std::size_t k = 0; k < a.entries.size(); ++k) {
    const ScheduledTask &x = a.entries[k], &y = b.entries[k];
    if (x.task != y.task || x.depart != y.depart || x.arrival != y.arrival || x.start != y.start || x.end != y.end ||
        x.travel != y.travel || x.waiting != y.waiting)
      return "entry " + std::to_string(k);
  }
  if (a.dropped.size() != b.dropped.size()) return "dropped count";
  for (std::size_t k = 0; k < a.dropped.size(); ++k)
    if (a.dropped[k].task != b.dropped[k].task || a.dropped[k].reason != b.dropped[k].reason)
      return "dropped " + std::to_string(k);
  return "";
}

Schedule solve_with_polls(const Problem& p, std::int64_t polls, std::uint64_t seed = 1) {
  const PollBudgetStop stop(polls);
  return DefaultScheduler({.seed = seed}).solve(p, stop);
}

// A robot-like day on a grid: a task every few minutes, windows of 20 min to 3 h.
Problem robot_like(std::size_t tasks, std::uint64_t seed) {
  RandomProblemOptions o;
  o.tasks = tasks;
  o.seed = seed;
  const Problem grid = random_problem(o);  // for its Manhattan travel between tasks+1 places
  testing::RobotDayOptions d;
  d.tasks = tasks;
  d.seed = seed;
  d.horizon = minutes(4) * static_cast<std::int64_t>(tasks);
  return testing::robot_day(grid.travel, d);
}

// The same day with travel twice as slow before 09:00, easing off by 10:00 (FIFO: slope > -1).
Problem rush_hour(Problem p) {
  const std::size_t n = p.travel->location_count();
  std::vector<Duration> normal(n * n), slow(n * n);
  for (std::size_t a = 0; a < n; ++a)
    for (std::size_t b = 0; b < n; ++b) {
      normal[a * n + b] = p.travel->travel(a, b, p.robot.time);
      slow[a * n + b] = 2 * normal[a * n + b];
    }
  const Time nine = Time{} + hours(9);
  p.travel = std::make_shared<PiecewiseLinearTravel>(
      PiecewiseLinearTravel::create(n, {{nine, slow}, {nine + hours(1), normal}}).value());
  return p;
}

Problem deliveries(std::size_t tasks, std::uint64_t seed) {
  RandomProblemOptions o;
  o.tasks = tasks;
  o.seed = seed;
  o.deliveries = tasks / 4;
  o.capacity = 2;
  o.same_looking = true;
  o.precedence = true;
  o.horizon_s = 3 * 3600;
  o.min_width_s = 1800;
  o.max_width_s = 3 * 3600;
  return random_problem(o);
}

struct Case {
  const char* name;
  Problem problem;
};

std::vector<Case> cases() {
  return {{"robot day, 10 tasks", robot_like(10, 3)},
          {"robot day, 25 tasks", robot_like(25, 4)},
          {"robot day, 40 tasks", robot_like(40, 5)},
          {"rush hour, 30 tasks", rush_hour(robot_like(30, 6))},
          {"deliveries, 16 tasks", deliveries(16, 8)},
          {"robot day, 120 tasks", robot_like(120, 8)}};
}

const std::vector<std::int64_t> kBudgets = {0, 1, 7, 60, 500, 3000, 20000};

TEST(PollBudget, IdenticalInputAndBudgetGiveIdenticalSchedules) {
  const std::vector<Case> all = cases();
  // First pass: every case at every budget.
  std::vector<std::vector<Schedule>> first(all.size());
  for (std::size_t c = 0; c < all.size(); ++c)
    for (std::int64_t b : kBudgets) first[c].push_back(solve_with_polls(all[c].problem, b));
  // Second pass: fresh copies of the problems, in the opposite order, with the heap stirred, so
  // that neither leftover state nor addresses could go unnoticed.
  std::vector<std::unique_ptr<std::string>> stir;
  for (std::size_t c = all.size(); c-- > 0;) {
    const Problem copy = all[c].problem;
    for (std::size_t k = kBudgets.size(); k-- > 0;) {
      stir.push_back(std::make_unique<std::string>(17 * (c + k) + 1, 'x'));
      const Schedule again = solve_with_polls(copy, kBudgets[k]);
      EXPECT_EQ(difference(first[c][k], again), "") << all[c].name << ", " << kBudgets[k] << " polls";
      if (complete(again)) {
        EXPECT_TRUE(check_schedule(copy, again).ok()) << all[c].name << ", " << kBudgets[k];
      }
    }
  }
}

TEST(PollBudget, OneSolverObjectKeepsNoStateBetweenSolves) {
  const std::vector<Case> all = cases();
  DefaultScheduler solver({.seed = 1});
  const PollBudgetStop first_stop(3000);
  const Schedule first = solver.solve(all[2].problem, first_stop);
  for (const Case& c : all) {
    const PollBudgetStop stop(3000);
    (void)solver.solve(c.problem, stop);
  }
  const PollBudgetStop again_stop(3000);
  EXPECT_EQ(difference(first, solver.solve(all[2].problem, again_stop)), "");
}

TEST(PollBudget, ALargerBudgetNeverGivesAWorseSchedule) {
  for (const Case& c : cases()) {
    std::optional<Duration> previous;
    for (std::int64_t b : kBudgets) {
      const Schedule s = solve_with_polls(c.problem, b);
      if (!complete(s)) {
        EXPECT_FALSE(previous) << c.name << ": found at fewer polls, lost at " << b;
        continue;
      }
      if (previous) {
        EXPECT_LE(s.objective, *previous) << c.name << ", " << b << " polls";
      }
      previous = s.objective;
    }
    EXPECT_TRUE(previous) << c.name << ": no schedule even with " << kBudgets.back() << " polls";
  }
}

TEST(PollBudget, TheRecommendedBudgetReachesTheProvedOptimumOnSmallDays) {
  // docs/scheduling.md recommends 2000 polls for 10-40 tasks; on days the exact program proves
  // quickly, that budget is enough for the proof.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const Problem p = robot_like(12, seed);
    const Schedule proved = DefaultScheduler{}.solve(p, NeverStop{});
    ASSERT_EQ(proved.status, SolveStatus::kOptimal) << seed;
    const Schedule s = solve_with_polls(p, 2000);
    EXPECT_EQ(s.status, SolveStatus::kOptimal) << seed;
    EXPECT_EQ(s.objective, proved.objective) << seed;
  }
}

RC_GTEST_PROP(PollBudgetProperties, TwoRunsWithTheSameBudgetAgree, ()) {
  RandomProblemOptions o;
  o.tasks = *rc::gen::inRange<std::size_t>(2, 30);
  o.seed = *rc::gen::inRange<std::uint64_t>(1, 1000000);
  o.deliveries = *rc::gen::inRange<std::size_t>(0, 3);
  o.capacity = *rc::gen::inRange<std::int64_t>(0, 3);
  o.same_looking = *rc::gen::arbitrary<bool>();
  o.precedence = *rc::gen::arbitrary<bool>();
  const Problem p = random_problem(o);
  RC_PRE(validate(p).ok());
  const auto polls = *rc::gen::inRange<std::int64_t>(0, 5000);
  const auto seed = *rc::gen::inRange<std::uint64_t>(1, 100);
  const Schedule a = solve_with_polls(p, polls, seed);
  const Schedule b = solve_with_polls(p, polls, seed);
  RC_ASSERT(difference(a, b) == "");
  if (complete(a)) RC_ASSERT(check_schedule(p, a).ok());
}

}  // namespace
}  // namespace rondo::schedule
