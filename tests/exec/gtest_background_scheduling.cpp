// ExecutorOptions::background_scheduling on a ScriptedRobot (scripted_robot.h): a burst of
// requests gives one reschedule, the old schedule runs while the worker solves, and an answer the
// book has moved past is not applied. The worker's scheduler is a real one behind a gate the test
// opens, so what is in flight is decided by the test, not by the machine's speed.
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "rondo/schedule/default_scheduler.h"
#include "rondo/store/task_table.h"
#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

// DefaultScheduler behind a gate: while closed, every solve waits (on the worker thread) until
// the test opens it.
class GatedScheduler final : public schedule::Scheduler {
 public:
  std::string_view name() const override { return "gated"; }
  schedule::Schedule solve(const schedule::Problem& problem, const schedule::StopCondition& stop) override {
    {
      std::unique_lock lock(mutex_);
      ++waiting_;
      changed_.notify_all();
      changed_.wait(lock, [this] { return open_ || passes_ > 0; });
      if (!open_) --passes_;
      --waiting_;
    }
    return inner_.solve(problem, stop);
  }
  void set_open(bool open) {
    {
      std::lock_guard lock(mutex_);
      open_ = open;
    }
    changed_.notify_all();
  }
  // Lets one solve through the closed gate.
  void pass_one() {
    {
      std::lock_guard lock(mutex_);
      ++passes_;
    }
    changed_.notify_all();
  }
  // True while a solve waits at the closed gate.
  bool holding_a_solve() {
    std::lock_guard lock(mutex_);
    return waiting_ > 0;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool open_ = true;
  int waiting_ = 0;
  int passes_ = 0;
  schedule::DefaultScheduler inner_;
};

ExecutorOptions background(bool forget_finished = false, std::size_t offered = 64) {
  ExecutorOptions o;
  o.background_offered = offered;
  o.background_scheduling = true;
  o.background_interval = Duration{0};  // the test decides what is merged
  o.forget_finished = forget_finished;
  return o;
}

class Background : public ScriptedExecutor {
 public:
  // `forget_finished`: as rondo serve, finished tasks leave the book.
  explicit Background(GatedScheduler*& gate, bool forget_finished = false, std::size_t offered = 64)
      : ScriptedExecutor(background(forget_finished, offered), scenario_map(),
                         ExecutorParts{.scheduler = make_gate(gate)}) {}
  SimClock& clock() { return clock_; }
  // Delivers what the worker posts until `done`, for 60 s of wall time at most.
  bool settle_until(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < deadline) {
      settle();
      if (done()) return true;
      std::this_thread::yield();
    }
    return false;
  }
  const ExecutorStats& stats() { return executor().stats(); }
  bool planned(const std::string& id) { return executor().tasks().at(id).planned_start.has_value(); }

 private:
  static std::unique_ptr<schedule::Scheduler> make_gate(GatedScheduler*& gate) {
    auto g = std::make_unique<GatedScheduler>();
    gate = g.get();
    return g;
  }
};

TEST(BackgroundScheduling, ABurstOfSubmissionsGivesOneReschedule) {
  GatedScheduler* gate = nullptr;
  Background s(gate);
  s.fleet().start();
  s.settle();
  constexpr int kBurst = 8;
  const char* nodes[] = {"Office", "Lab", "Kitchen", "Hall"};
  for (int i = 0; i < kBurst; ++i)  // as the HTTP threads post them
    s.clock().post([&s, &nodes, i] {
      const Task t = task("T" + std::to_string(i), nodes[i % 4], s.at("08:00"), s.at("18:00"), minutes(5));
      ASSERT_TRUE(s.fleet().add_task(t, "api").ok());
    });
  ASSERT_TRUE(s.settle_until([&] { return s.stats().background_runs >= 1; }));
  s.settle();
  EXPECT_EQ(s.stats().background_runs, 1);
  EXPECT_EQ(s.stats().background_stale, 0);
  int planned_or_running = 0;
  for (int i = 0; i < kBurst; ++i) {
    const std::string id = "T" + std::to_string(i);
    if (s.planned(id) || s.executor().current_task() == id) ++planned_or_running;
    // One reschedule for all of them: the same merged reason in every "scheduled" event.
    EXPECT_NE(s.reason_of(id, "scheduled").find("new tasks"), std::string::npos) << id;
  }
  EXPECT_EQ(planned_or_running, kBurst);
  EXPECT_TRUE(s.robot().driving());  // the first of them is on its way
}

TEST(BackgroundScheduling, TheOldScheduleRunsMeanwhileAndATaskEndedMeanwhileIsLeftOutOfTheAnswer) {
  GatedScheduler* gate = nullptr;
  Background s(gate);
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  s.fleet().start();
  ASSERT_TRUE(s.settle_until([&] { return s.robot().driving(); }));  // A is planned and on its way
  EXPECT_EQ(s.stats().background_runs, 1);

  gate->set_open(false);
  // Answered after its commit, not after the reschedule: the worker is stuck at the gate.
  ASSERT_TRUE(s.fleet().add_task(task("B", "Lab", s.at("08:00"), s.at("12:00"), minutes(5)), "api").ok());
  ASSERT_TRUE(s.fleet().add_task(task("D", "Hall", s.at("08:00"), s.at("12:00"), minutes(5)), "api").ok());
  EXPECT_TRUE(store::get_task(s.store(), "B").ok());
  // B's and D's problem is in flight. The clock's posts are delivered meanwhile: the worker says
  // it is ready for it only after A's answer, in a post of its own.
  ASSERT_TRUE(s.settle_until([&] { return gate->holding_a_solve(); }));
  EXPECT_FALSE(s.planned("B"));
  // The old schedule goes on meanwhile: A drives to the Office and acts.
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  EXPECT_TRUE(s.robot().acting());
  EXPECT_EQ(s.state("A"), "acting");
  // Meanwhile C comes and B is cancelled: the answer in flight plans B and D. It is applied
  // without B (D's place is still good), and C's reschedule follows.
  ASSERT_TRUE(s.fleet().add_task(task("C", "Kitchen", s.at("08:00"), s.at("12:00"), minutes(5)), "api").ok());
  ASSERT_TRUE(s.executor().cancel_task("B", "not needed").ok());
  gate->set_open(true);
  ASSERT_TRUE(s.settle_until([&] { return s.planned("C"); }));
  EXPECT_EQ(s.stats().background_runs, 3);  // A; B and D; C
  EXPECT_EQ(s.stats().background_stale, 0);
  EXPECT_EQ(s.state("B"), "cancelled");
  EXPECT_FALSE(s.planned("B"));
  EXPECT_EQ(s.code_of("B", "scheduled"), "");  // B's part of the answer never reached the book
  EXPECT_TRUE(s.planned("D"));
  EXPECT_EQ(s.state("A"), "acting");  // and the running task was left alone
}

// Under a load that cancels tasks soon after they are accepted (as scripts/failover-test with
// FAILOVER_CANCEL=1), every problem holds a task that ends before its answer comes back. The
// answers must still be applied: a takeover starts with no schedule, and its robot would wait
// for one for as long as the load lasts.
TEST(BackgroundScheduling, AnswersAreAppliedWhileEveryProblemHoldsATaskCancelledMeanwhile) {
  GatedScheduler* gate = nullptr;
  Background s(gate, /*forget_finished=*/true);
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(5)), "test").ok());
  gate->set_open(false);
  s.fleet().start();
  for (int round = 0; round < 4; ++round) {
    ASSERT_TRUE(s.settle_until([&] { return gate->holding_a_solve(); })) << round;
    // While it is solved, the problem's newest task is cancelled and new ones come.
    const std::string gone = round == 0 ? "A" : "X" + std::to_string(round - 1);
    ASSERT_TRUE(s.executor().cancel_task(gone, "not needed").ok()) << gone;
    ASSERT_TRUE(s.fleet()
                    .add_task(task("X" + std::to_string(round), round % 2 ? "Lab" : "Kitchen", s.at("08:00"),
                                   s.at("12:00"), minutes(5)),
                              "api")
                    .ok());
    ASSERT_TRUE(
        s.fleet()
            .add_task(task("K" + std::to_string(round), "Hall", s.at("08:00"), s.at("18:00"), minutes(5)), "api")
            .ok());
    gate->pass_one();
    ASSERT_TRUE(s.settle_until([&] { return s.stats().background_runs >= round + 1; })) << round;
  }
  gate->set_open(true);
  EXPECT_EQ(s.stats().background_stale, 0);
  EXPECT_TRUE(s.planned("K0") || s.executor().current_task() == "K0");
}

TEST(BackgroundScheduling, AChangeMeanwhileMakesTheAnswerStale) {
  GatedScheduler* gate = nullptr;
  Background s(gate);
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("10:00"), s.at("11:00"), minutes(5)), "test").ok());
  gate->set_open(false);
  s.fleet().start();
  ASSERT_TRUE(s.settle_until([&] { return gate->holding_a_solve(); }));
  // A's window moves while its first problem is solved: that answer (10:00) must not be used.
  const TimeWindow later{s.at("14:00"), s.at("15:00")};
  ASSERT_TRUE(s.executor().update_task("A", later, std::nullopt).ok());
  gate->set_open(true);
  ASSERT_TRUE(s.settle_until([&] { return s.stats().background_runs >= 2 && s.planned("A"); }));
  EXPECT_EQ(s.stats().background_stale, 1);
  EXPECT_GE(*s.executor().tasks().at("A").planned_start, s.at("14:00"));
}

// A task added while the worker is busy waits to join the next problem; cancelled meanwhile and
// swept from the book (forget_finished, as rondo serve), it must not be in that problem. This is
// what a takeover under load met: the restore's first problem took seconds, tasks cancelled 2 s
// after acceptance left the book before it came back, and building the next problem looked them
// up (std::out_of_range, "map::at", ended the new active).
TEST(BackgroundScheduling, ATaskThatLeftTheBookBeforeItsProblemWasBuiltIsNotInIt) {
  GatedScheduler* gate = nullptr;
  Background s(gate, /*forget_finished=*/true);
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("10:00"), s.at("11:00"), minutes(5)), "test").ok());
  gate->set_open(false);
  s.fleet().start();
  ASSERT_TRUE(s.settle_until([&] { return gate->holding_a_solve(); }));  // A's problem in flight
  ASSERT_TRUE(s.fleet().add_task(task("B", "Lab", s.at("12:00"), s.at("13:00"), minutes(5)), "api").ok());
  ASSERT_TRUE(s.fleet().add_task(task("C", "Kitchen", s.at("12:00"), s.at("14:00"), minutes(5)), "api").ok());
  ASSERT_TRUE(s.executor().cancel_task("B", "not needed").ok());
  s.settle();  // the sweep: B leaves the book
  ASSERT_FALSE(s.executor().book().contains("B"));
  gate->set_open(true);
  ASSERT_TRUE(s.settle_until([&] { return s.planned("C"); }));
  EXPECT_EQ(s.state("B"), "cancelled");
  EXPECT_EQ(s.code_of("B", "scheduled"), "");
  EXPECT_TRUE(s.planned("A"));
}

// A restore (a restart, a takeover) brings every queued task back as new to the scheduler. A
// problem takes at most background_offered of them, the soonest due first, and the next ones take
// the rest: the task due now is planned in the first problem, however many wait for tomorrow.
TEST(BackgroundScheduling, AtStartTheSoonestDueTasksComeFirstAndTheRestInLaterProblems) {
  GatedScheduler* gate = nullptr;
  Background s(gate, /*forget_finished=*/true, /*offered=*/3);
  const char* nodes[] = {"Office", "Lab", "Kitchen", "Hall"};
  for (int i = 0; i < 9; ++i)
    ASSERT_TRUE(
        s.fleet()
            .add_task(task("later-" + std::to_string(i), nodes[i % 4], s.at("13:00"), s.at("18:00"), minutes(5)),
                      "test")
            .ok());
  ASSERT_TRUE(s.fleet().add_task(task("due", "Kitchen", s.at("08:00"), s.at("08:30"), minutes(5)), "test").ok());
  gate->set_open(false);
  s.fleet().start();
  ASSERT_TRUE(s.settle_until([&] { return gate->holding_a_solve(); }));
  gate->pass_one();
  ASSERT_TRUE(s.settle_until([&] { return s.stats().background_runs >= 1; }));
  EXPECT_TRUE(s.planned("due") || s.executor().current_task() == "due");
  int planned = 0;
  for (int i = 0; i < 9; ++i) planned += s.planned("later-" + std::to_string(i)) ? 1 : 0;
  EXPECT_EQ(planned, 2);  // three in the first problem
  gate->set_open(true);
  ASSERT_TRUE(s.settle_until([&] {
    for (int i = 0; i < 9; ++i)
      if (!s.planned("later-" + std::to_string(i))) return false;
    return true;
  }));
  EXPECT_GE(s.stats().background_runs, 4);
  EXPECT_EQ(s.stats().background_stale, 0);
  EXPECT_EQ(s.executor().current_task(), "due");
}

}  // namespace
}  // namespace rondo::exec::testing
