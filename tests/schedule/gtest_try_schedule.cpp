// The drop scenarios of docs/scheduling.md, one table row each: an oversubscribed window, priority
// order respected (and a dropped task given back when it fits), a higher-priority task that
// preempts an interruptible running task, and one blocked by a non-interruptible running task.
#include "rondo/schedule/try_schedule.h"

#include <gtest/gtest.h>

#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "ticking_deadline.h"

namespace rondo::schedule {
namespace {

const Time kTen = *parse_time("2026-03-02T10:00:00Z");

// dock = 0, room A = 1, room B = 2; two minutes between any two places.
Problem base_problem() {
  Problem p;
  const Duration two = minutes(2), zero{0};
  p.travel = std::make_shared<MatrixTravel>(
      MatrixTravel::create(3, {zero, two, two, two, zero, two, two, two, zero}).value());
  p.location_names = {"dock", "A", "B"};
  p.robot.time = kTen;
  return p;
}

ProblemTask task(std::string id, LocationIndex at, int from_min, int to_min, int duration_min, int priority) {
  ProblemTask t;
  t.id = std::move(id);
  t.start_location = t.end_location = at;
  t.release = kTen + minutes(from_min);
  t.deadline = kTen + minutes(to_min);
  t.duration = minutes(duration_min);
  t.priority = priority;
  return t;
}

struct Scenario {
  std::string name;
  TryScheduleRequest request;
  TryScheduleOutcome outcome;
  std::vector<std::string> dropped;                 // ids, in task order
  std::vector<std::string> reason_contains;         // one per dropped task
  std::string preempt_contains;
};

std::vector<Scenario> scenarios() {
  std::vector<Scenario> all;
  {
    Scenario s{"oversubscribed window", {base_problem(), {}}, TryScheduleOutcome::kSomeDropped, {"p1", "p2"},
               {"window 10:00–10:15", "window 10:00–10:15"}, ""};
    for (int k = 1; k <= 5; ++k) {
      s.request.problem.tasks.push_back(task("p" + std::to_string(k), 1, 0, 15, 4, k));
      s.request.new_tasks.push_back(static_cast<std::size_t>(k - 1));
    }
    all.push_back(std::move(s));
  }
  {
    Scenario s{"priority order respected, a dropped task that fits is given back",
               {base_problem(), {0, 1, 2}},
               TryScheduleOutcome::kSomeDropped,
               {"low-A"},
               {"dropped for higher-priority tasks high-A"},
               ""};
    s.request.problem.tasks = {task("high-A", 1, 0, 8, 5, 5), task("low-A", 1, 0, 8, 5, 1),
                               task("low-B", 2, 0, 60, 5, 1)};
    all.push_back(std::move(s));
  }
  {
    Scenario s{"higher priority preempts an interruptible running task",
               {base_problem(), {0}, RunningTask{"patrol", 2, true}},
               TryScheduleOutcome::kPreemptRunning,
               {},
               {},
               "outrank the running task patrol"};
    s.request.problem.robot.time = kTen + minutes(20);  // patrol ends at 10:20
    s.request.problem.tasks = {task("urgent", 1, 0, 10, 3, 5)};
    all.push_back(std::move(s));
  }
  {
    Scenario s{"a non-interruptible running task blocks a higher-priority one",
               {base_problem(), {0}, RunningTask{"talking", 2, false}},
               TryScheduleOutcome::kSomeDropped,
               {"urgent"},
               {"cannot be reached from the robot's position at 10:20 UTC (travel 2m); the running task talking cannot "
                "be interrupted"},
               ""};
    s.request.problem.robot.time = kTen + minutes(20);
    s.request.problem.tasks = {task("urgent", 1, 0, 10, 3, 5)};
    all.push_back(std::move(s));
  }
  {
    // The same task offered again after an earlier drop may be dropped, but never preempts.
    Scenario s{"a task offered again does not preempt an interruptible running task",
               {base_problem(), {0}, RunningTask{"patrol", 2, true}, {0}},
               TryScheduleOutcome::kSomeDropped,
               {"urgent"},
               {"cannot be reached from the robot's position at 10:20"},
               ""};
    s.request.problem.robot.time = kTen + minutes(20);
    s.request.problem.tasks = {task("urgent", 1, 0, 10, 3, 5)};
    all.push_back(std::move(s));
  }
  {
    Scenario s{"everything fits", {base_problem(), {1}}, TryScheduleOutcome::kAllScheduled, {}, {}, ""};
    s.request.problem.tasks = {task("old", 1, 0, 60, 5, 0), task("new", 2, 0, 60, 5, 0)};
    all.push_back(std::move(s));
  }
  return all;
}

TEST(TrySchedule, DropScenariosOfTheDocs) {
  for (const Scenario& sc : scenarios()) {
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {  // ties are broken at random: any seed works
      DefaultScheduler solver;
      std::mt19937_64 rng(seed);
      const TryScheduleResult r = try_schedule(sc.request, solver, NeverStop{}, rng);
      ASSERT_EQ(r.outcome, sc.outcome) << sc.name;
      if (r.outcome == TryScheduleOutcome::kPreemptRunning) {
        EXPECT_NE(r.preempt_reason.find(sc.preempt_contains), std::string::npos) << sc.name << ": " << r.preempt_reason;
        continue;
      }
      const CheckReport check = check_schedule(sc.request.problem, r.schedule);
      EXPECT_TRUE(check.ok()) << sc.name << ": " << check.summary();
      std::vector<std::string> dropped;
      for (const auto& d : r.schedule.dropped) dropped.push_back(sc.request.problem.tasks[d.task].id);
      ASSERT_EQ(dropped, sc.dropped) << sc.name;
      for (std::size_t k = 0; k < dropped.size(); ++k)
        EXPECT_NE(r.schedule.dropped[k].reason.find(sc.reason_contains[k]), std::string::npos)
            << sc.name << ": " << r.schedule.dropped[k].reason;
    }
  }
}

TEST(TrySchedule, RestoringNeverDropsMoreThanThePaperRule) {
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    TryScheduleRequest req{base_problem(), {}};
    std::mt19937_64 gen(seed);
    for (int k = 0; k < 9; ++k) {
      const int from = static_cast<int>(gen() % 30);
      req.problem.tasks.push_back(task("t" + std::to_string(k), 1 + gen() % 2, from, from + 8 + static_cast<int>(gen() % 10),
                                       3, static_cast<int>(gen() % 4)));
      req.new_tasks.push_back(static_cast<std::size_t>(k));
    }
    DefaultScheduler solver;
    std::mt19937_64 rng_a(seed), rng_b(seed);
    req.policy = DropPolicy::kPaper;
    const auto paper = try_schedule(req, solver, NeverStop{}, rng_a);
    req.policy = DropPolicy::kPaperThenRestore;
    const auto ours = try_schedule(req, solver, NeverStop{}, rng_b);
    EXPECT_LE(ours.schedule.dropped.size(), paper.schedule.dropped.size());
    EXPECT_TRUE(check_schedule(req.problem, paper.schedule).ok()) << check_schedule(req.problem, paper.schedule).summary();
    EXPECT_TRUE(check_schedule(req.problem, ours.schedule).ok()) << check_schedule(req.problem, ours.schedule).summary();
  }
}

constexpr std::int64_t kTicks = 20'000;

// The solver, counting the calls made once the stop had fired.
class WatchedSolver final : public Scheduler {
 public:
  std::string_view name() const override { return "watched"; }
  Schedule solve(const Problem& problem, const StopCondition& stop) override {
    ++calls;
    if (stop.should_stop()) ++calls_after_stop;
    return inner.solve(problem, stop);
  }
  DefaultScheduler inner{DefaultSchedulerOptions{.exact_max_tasks = 0}};
  int calls = 0;
  int calls_after_stop = 0;
};

// A takeover restores many queued tasks as new at once, far more than fit before their deadlines:
// the budget (a deadline, as the executor's background solve has) runs out inside the drop loop.
// Before, every further attempt failed at once and dropped more, so every new task was dropped,
// the urgent one too, and the loop kept calling the solver long after the deadline.
TEST(TrySchedule, ABudgetThatEndsInTheDropLoopKeepsWhatFitsAndCallsTheSolverNoMore) {
  TryScheduleRequest req{base_problem(), {}};
  req.problem.tasks.push_back(task("old", 1, 0, 120, 5, 0));
  req.problem.tasks.push_back(task("urgent", 2, 0, 20, 3, 5));
  req.new_tasks.push_back(1);
  for (int k = 0; k < 40; ++k) {
    req.problem.tasks.push_back(task("n" + std::to_string(k), k % 2 == 0 ? 1U : 2U, 0, 30, 4, 1));
    req.new_tasks.push_back(req.problem.tasks.size() - 1);
  }
  WatchedSolver solver;
  testing::TickingDeadline budget(kTicks);
  std::mt19937_64 rng(7);
  const TryScheduleResult out = try_schedule(req, solver, budget, rng);

  EXPECT_GT(budget.readings(), kTicks) << "the budget is meant to end inside the drop loop";
  EXPECT_LE(solver.calls_after_stop, 1) << solver.calls << " solver calls";
  EXPECT_LE(budget.readings_past_the_deadline(), 5);
  ASSERT_EQ(out.outcome, TryScheduleOutcome::kSomeDropped);
  EXPECT_TRUE(check_schedule(req.problem, out.schedule).ok()) << check_schedule(req.problem, out.schedule).summary();
  std::vector<std::string> kept;
  for (const ScheduledTask& e : out.schedule.entries) kept.push_back(req.problem.tasks[e.task].id);
  EXPECT_NE(std::find(kept.begin(), kept.end(), "old"), kept.end());
  EXPECT_NE(std::find(kept.begin(), kept.end(), "urgent"), kept.end());
  EXPECT_GE(kept.size(), 6U);  // old, urgent and at least four of the forty
  EXPECT_EQ(kept.size() + out.schedule.dropped.size(), req.problem.tasks.size());
}

}  // namespace
}  // namespace rondo::schedule
