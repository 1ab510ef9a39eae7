// Executor::restore: the executor rebuilt from its store after a restart, on the real SimRobot in
// the calm scenario world. A "crash" is the executor, robot and clock destroyed with nothing said
// to the store (the executor writes nothing when it is destroyed, as after a SIGKILL); the next
// life opens the same file, at the latest time the store holds (or later: a power cut), with the
// robot at its stored node.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <set>

#include "rondo/core/routine.h"
#include "rondo/core/task_codec.h"
#include "rondo/store/events.h"
#include "rondo/store/read_back.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/task_table.h"
#include "rondo/store/traversal_log.h"
#include "scenario.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

// One life of the executive on a store file: a clock, a robot, an executor.
class Life {
 public:
  Life(const std::filesystem::path& db, Time now, const std::string& robot_at = "Dock")
      : map_(scenario_map()),
        zone_(TimeZone::named("Europe/London").value()),
        clock_(now),
        store_(store::Store::open(db, {.sync_commits = false}).value()) {
    auto doc = Document::parse(kCalmWorld, DocumentFormat::kYaml, "world.yaml").value();
    world_ = std::make_unique<sim::SimWorld>(sim::decode_world(doc, ".", map_, zone_).value());
    const map::NodeIndex dock = *map_.find_node("Dock");
    robot_ = std::make_unique<sim::SimRobot>(clock_, map_, *world_,
                                             sim::SimRobotOptions{.start = *map_.find_node(robot_at), .dock = dock});
    fleet_ = std::make_unique<fleet::Fleet>(clock_, map_, store_, zone_, ExecutorOptions{.dock = dock});
    executor_ = &fleet_->add_robot(*robot_, ExecutorOptions{.dock = dock});
  }
  ~Life() {
    fleet_.reset();
    robot_.reset();
  }

  fleet::Fleet& fleet() { return *fleet_; }
  Executor& executor() { return *executor_; }
  store::Store& store() { return store_; }
  SimClock& clock() { return clock_; }
  Time at(const std::string& local) const { return zone_.parse_time("2026-11-23T" + local).value(); }
  void run_until(const std::string& local) { clock_.run_until(at(local)); }
  std::string state(const std::string& id) const { return to_string(executor_->tasks().at(id).state); }

 private:
  map::TopoMap map_;
  TimeZone zone_;
  SimClock clock_;
  store::Store store_;
  std::unique_ptr<sim::SimWorld> world_;
  std::unique_ptr<sim::SimRobot> robot_;
  std::unique_ptr<fleet::Fleet> fleet_;
  Executor* executor_ = nullptr;
};

// Where the next life starts: the latest stored time, the robot's stored node.
struct Resume {
  Time at{};
  std::string node;
};
Resume resume_point(const std::filesystem::path& db) {
  auto store = store::Store::open(db, {.mode = store::OpenMode::kReadOnly}).value();
  const store::StoredRun back = store::read_back(store, "robot").value();
  return {back.latest().value(), back.robot ? back.robot->node : "Dock"};
}

std::vector<store::Event> events_of(const std::filesystem::path& db, const std::string& id) {
  auto store = store::Store::open(db, {.mode = store::OpenMode::kReadOnly}).value();
  return store::read_events_of(store, id).value();
}

// Five weeks of Dock_Hall before the run, every 30 minutes: failing on Wednesdays 13:00-17:00.
void weekly_history(store::Store& store, Time start) {
  std::vector<Traversal> log;
  for (Time t = start - hours(24 * 35); t < start; t += minutes(30)) {
    const auto since_monday = (t - (start - hours(24 * 35))) % hours(24 * 7);
    const bool closed = since_monday >= hours(24 * 2 + 13) && since_monday < hours(24 * 2 + 17);
    log.push_back({"Dock_Hall", "Dock", "Hall", t, seconds(10), !closed, ""});
  }
  ASSERT_TRUE(store::add_traversals(store, log).ok());
}

bool dock_hall_weekly(Executor& e) {
  const auto& models = e.models().models();
  if (!models) return false;
  const learn::EpisodeEdgeModel* m = models->model(*models->index_of("Dock_Hall"));
  return m != nullptr && m->weekly().weekly;
}

// The live weekly term (issue 37, point 2): the first refit learns the week from the days the
// memory can use, the store keeps the memory, and a restart reads it back, adds no day twice, and
// plans with the term at once; a memory that cannot be read is said so and learned afresh.
TEST(ExecutorRestore, TheWeeklyMemoryComesBackAndNoDayIsAddedTwice) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T00:00").value();
  std::string saved;
  {
    Life first(db, start);
    weekly_history(first.store(), start);
    first.fleet().start();
    first.run_until("03:00");  // past the refit at 02:00
    EXPECT_TRUE(dock_hall_weekly(first.executor()));
    auto stored = store::get_meta(first.store(), "learn.weekly_memory");
    ASSERT_TRUE(stored && *stored);
    saved = **stored;
  }
  {
    Life second(db, resume_point(db).at + minutes(30));
    ASSERT_TRUE(second.fleet().restore());
    second.fleet().start();
    EXPECT_TRUE(dock_hall_weekly(second.executor())) << "the term is planned with before the next refit";
    EXPECT_EQ(store::get_meta(second.store(), "learn.weekly_memory").value().value(), saved);
    EXPECT_TRUE(second.executor().write_errors().empty());
    ASSERT_TRUE(store::set_meta(second.store(), "learn.weekly_memory", "{not json"));
  }
  Life third(db, resume_point(db).at + hours(1));
  ASSERT_TRUE(third.fleet().restore());
  ASSERT_EQ(third.executor().write_errors().size(), 1u);
  EXPECT_THAT(third.executor().write_errors()[0], HasSubstr("learned afresh"));
  EXPECT_TRUE(dock_hall_weekly(third.executor()));
  // Learned again from the same days: the same counts (its evidence was scored against this
  // refit's pooled rate, a little different from the first's).
  const Json again = Json::parse(store::get_meta(third.store(), "learn.weekly_memory").value().value());
  const Json before = Json::parse(saved);
  EXPECT_EQ(again["next_day"], before["next_day"]);
  EXPECT_EQ(again["edges"]["Dock_Hall"]["slots"], before["edges"]["Dock_Hall"]["slots"]);
}

TEST(ExecutorRestore, ARunningTaskComesBackInterruptedThenQueuedAndIsCompleted) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  {
    Life first(db, start);
    first.fleet().start();
    ASSERT_TRUE(first.fleet().add_task(task("A", "Office", first.at("09:00"), first.at("10:00"), minutes(20)), "test"));
    first.run_until("09:05");
    ASSERT_EQ(first.state("A"), "acting");
  }  // the crash
  const Resume r = resume_point(db);
  EXPECT_EQ(r.node, "Office");  // the robot's last known node
  Life second(db, r.at, r.node);
  ASSERT_TRUE(second.fleet().restore());
  EXPECT_EQ(second.state("A"), "queued");
  EXPECT_EQ(second.executor().tasks().at("A").outcome, Outcome::kInterrupted);
  second.fleet().start();
  second.run_until("10:00");
  EXPECT_EQ(second.state("A"), "succeeded");
  EXPECT_TRUE(second.executor().write_errors().empty());

  // The event log tells the whole story, once: added, ..., acting, interrupted -> queued, ...,
  // succeeded.
  std::vector<std::string> states;
  int added = 0;
  for (const store::Event& e : events_of(db, "A")) {
    if (e.code == "added") ++added;
    if (e.event == "queued" && e.code == "interrupted") {
      EXPECT_THAT(e.reason, HasSubstr("the executive restarted while it ran"));
      EXPECT_THAT(e.reason, HasSubstr("back in the queue"));
    }
    if (parse_task_state(e.event)) states.push_back(e.event + (e.code.empty() ? "" : ":" + e.code));
  }
  EXPECT_EQ(added, 1);
  EXPECT_THAT(states, ::testing::IsSupersetOf({"acting:arrived", "queued:interrupted", "succeeded:done"}));
  EXPECT_EQ(second.executor().book().event_counts().at("queued").at(Outcome::kInterrupted), 1);
}

TEST(ExecutorRestore, AnInterruptedTaskWhoseWindowIsGoneFailsWithThatReason) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  {
    Life first(db, start);
    first.fleet().start();
    ASSERT_TRUE(first.fleet().add_task(task("A", "Office", first.at("09:00"), first.at("09:30"), minutes(20)), "test"));
    first.run_until("09:05");
    ASSERT_EQ(first.state("A"), "acting");
  }
  // The executive comes back after a power cut: at 09:20 the 20 minutes no longer fit by 09:30.
  Life second(db, start + minutes(80), resume_point(db).node);
  ASSERT_TRUE(second.fleet().restore());
  EXPECT_EQ(second.state("A"), "failed");
  EXPECT_EQ(second.executor().tasks().at("A").outcome, Outcome::kInterrupted);
  EXPECT_THAT(second.executor().tasks().at("A").reason, HasSubstr("its window no longer allows it"));
  auto stored = store::get_task(second.store(), "A").value();
  EXPECT_EQ(stored.state, "failed");
}

TEST(ExecutorRestore, ADroppedForNowTaskStaysDroppedForNowAndComesBackWhenACancelFreesItsWindow) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  std::map<std::string, std::map<Outcome, int>> counts_before;
  {
    Life first(db, start);
    first.fleet().start();
    ASSERT_TRUE(
        first.fleet().add_tasks({task("Big", "Office", first.at("09:00"), first.at("10:00"), minutes(50), 5),
                                 task("Small", "Kitchen", first.at("09:00"), first.at("10:00"), minutes(30), 1)},
                                "test"));
    first.run_until("08:30");
    ASSERT_TRUE(first.executor().tasks().at("Small").dropped_for_now.has_value());
    counts_before = first.executor().book().event_counts();
  }
  const Resume r = resume_point(db);
  Life second(db, r.at, r.node);
  ASSERT_TRUE(second.fleet().restore());
  const TaskRecord& small = second.executor().tasks().at("Small");
  EXPECT_EQ(small.state, TaskState::kQueued);
  ASSERT_TRUE(small.dropped_for_now.has_value());
  EXPECT_EQ(small.dropped_for_now->first, Outcome::kDroppedForHigherPriority);
  EXPECT_FALSE(second.executor().tasks().at("Big").dropped_for_now.has_value());
  // The book counts what happened before the restart as it did then.
  EXPECT_EQ(second.executor().book().event_counts(), counts_before);
  second.fleet().start();
  ASSERT_TRUE(second.executor().cancel_task("Big", "meeting moved").ok());
  second.run_until("11:00");
  EXPECT_EQ(second.state("Small"), "succeeded");
  EXPECT_EQ(second.state("Big"), "cancelled");
}

TEST(ExecutorRestore, ADroppedForNowTaskIsDroppedForGoodWhenItsWindowPassesAfterTheRestart) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  {
    Life first(db, start);
    first.fleet().start();
    ASSERT_TRUE(
        first.fleet().add_tasks({task("Big", "Office", first.at("09:00"), first.at("10:00"), minutes(50), 5),
                                 task("Small", "Kitchen", first.at("09:00"), first.at("10:00"), minutes(30), 1)},
                                "test"));
    first.run_until("08:30");
  }
  const Resume r = resume_point(db);
  Life second(db, r.at, r.node);
  ASSERT_TRUE(second.fleet().restore());
  second.fleet().start();
  second.run_until("11:00");
  EXPECT_EQ(second.state("Big"), "succeeded");
  EXPECT_EQ(second.state("Small"), "dropped");
  EXPECT_EQ(second.executor().tasks().at("Small").outcome, Outcome::kDroppedForHigherPriority);
}

TEST(ExecutorRestore, RoutineTasksAlreadyStoredAreNotMadeAgain) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  Routine patrol;
  patrol.name = "patrol";
  patrol.task = task("", "Lab", start, start, minutes(10));
  patrol.task.window.reset();
  patrol.window_start = hours(9);
  patrol.window_end = hours(11);
  {
    Life first(db, start);
    first.fleet().add_routines({patrol});
    first.fleet().start();
    first.run_until("09:05");
    ASSERT_EQ(first.executor().tasks().size(), 1u);
  }
  const Resume r = resume_point(db);
  Life second(db, r.at, r.node);
  second.fleet().add_routines({patrol});
  ASSERT_TRUE(second.fleet().restore());
  second.fleet().start();                       // makes today's routine tasks: the stored one is not made again
  second.clock().run_until(start + hours(30));  // and tomorrow's, at midnight
  EXPECT_TRUE(second.executor().write_errors().empty());
  const auto tasks = store::list_tasks(second.store()).value();
  std::set<std::string> ids;
  for (const auto& t : tasks) ids.insert(t.id);
  EXPECT_EQ(ids, (std::set<std::string>{"patrol@2026-11-23T09:00", "patrol@2026-11-24T09:00"}));
  EXPECT_EQ(second.executor().tasks().size(), 2u);
  for (const std::string& id : ids) {
    int added = 0;
    for (const store::Event& e : events_of(db, id)) added += e.code == "added";
    EXPECT_EQ(added, 1) << id;
  }
  EXPECT_EQ(second.state("patrol@2026-11-23T09:00"), "succeeded");
}

TEST(ExecutorRestore, FinalTasksComeBackFinalAndAQueuedOnDemandTaskRunsFirst) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  {
    Life first(db, start);
    first.fleet().start();
    ASSERT_TRUE(
        first.fleet().add_task(task("Early", "Office", first.at("08:05"), first.at("08:30"), minutes(5)), "test"));
    ASSERT_TRUE(first.fleet().add_task(task("Late", "Office", first.at("09:00"), first.at("12:00"), minutes(30), 1,
                                            /*interruptible=*/false),
                                       "test"));
    first.run_until("09:10");
    ASSERT_EQ(first.state("Early"), "succeeded");
    ASSERT_EQ(first.state("Late"), "acting");
    ASSERT_TRUE(first.fleet().add_task(on_demand("Ask", "Kitchen", minutes(5)), "test"));
    first.run_until("09:11");
    ASSERT_EQ(first.state("Ask"), "queued");  // waits for the task that cannot be interrupted
  }
  const Resume r = resume_point(db);
  Life second(db, r.at, r.node);
  ASSERT_TRUE(second.fleet().restore());
  const TaskRecord& early = second.executor().tasks().at("Early");
  EXPECT_EQ(early.state, TaskState::kSucceeded);
  EXPECT_EQ(early.outcome, Outcome::kDone);
  EXPECT_THAT(early.reason, HasSubstr("done"));
  EXPECT_EQ(early.source, "test");
  EXPECT_TRUE(early.ended.has_value());
  EXPECT_EQ(second.executor().task_order(), (std::vector<TaskId>{"Early", "Late", "Ask"}));
  second.fleet().start();
  second.run_until("12:00");
  EXPECT_EQ(second.state("Ask"), "succeeded");
  EXPECT_EQ(second.state("Late"), "succeeded");
  // The on-demand task went first after the restart.
  const auto succeeded = [&](const std::string& id) {
    for (const store::Event& e : events_of(db, id))
      if (e.event == "succeeded") return e.time;
    return Time{};
  };
  EXPECT_LT(succeeded("Ask"), succeeded("Late"));
}

TEST(ExecutorRestore, RestoreRunsOnlyBeforeStartAndOnAnEmptyBook) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  Life life(db, start);
  life.fleet().start();
  const Status late = life.fleet().restore();
  ASSERT_FALSE(late.ok());
  EXPECT_EQ(late.error().code, ErrorCode::kInternal);
}

// The deployment changed while the executive was down: a stored task on a node that is gone ends
// with that reason at the restart, and the rest runs.
TEST(ExecutorRestore, AStoredTaskOnANodeThatIsGoneEndsNoLongerValid) {
  const auto db = fresh_db_path();
  const Time start = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  {
    auto store = store::Store::open(db, {.sync_commits = false}).value();
    Task gone = task("Gone", "Office", start, start + hours(2), minutes(5));
    gone.start_node = "Attic";  // renamed away in the edited deployment
    const Task fine = task("Fine", "Office", start, start + hours(2), minutes(5));
    const store::TaskRow rows[] = {
        {.id = "Gone", .task = encode(gone), .state = "queued", .created = start, .updated = start},
        {.id = "Fine", .task = encode(fine), .state = "queued", .created = start, .updated = start}};
    ASSERT_TRUE(store::add_tasks(store, rows, "accepted", "added").ok());
  }
  Life next(db, start);
  ASSERT_TRUE(next.fleet().restore().ok());
  next.fleet().start();
  EXPECT_EQ(next.state("Gone"), "failed");
  EXPECT_EQ(next.executor().tasks().at("Gone").outcome, Outcome::kNoLongerValid);
  EXPECT_THAT(next.executor().tasks().at("Gone").reason, HasSubstr("'Attic' is not on the map"));
  next.run_until("10:00");
  EXPECT_EQ(next.state("Fine"), "succeeded");
}

// The battery estimator's learned state over a kill (issue 37 point 6): stored at the end of every
// task (and of every charge), taken back by restore(). On the scripted robot: three tasks at the
// Office, every edge costs 0.2 % of the battery and every action 0.5 %.
struct BatteryLife : ScriptedExecutor {
  BatteryLife() {
    for (const char* id : {"A", "B", "C"})
      EXPECT_TRUE(fleet().add_task(task(id, "Office", at("08:00"), at("12:00"), minutes(1)), "test").ok());
    fleet().start();
    for (int guard = 0; guard < 500; ++guard) {
      settle();
      if (state("C") == "succeeded") break;  // killed at the end of the last task
      if (robot().driving()) {
        clock_.run_until(clock_.now() + seconds(20));
        robot().battery_level -= 0.002;
        robot().finish_edge(EdgeOutcome::kSucceeded, seconds(20));
      } else if (robot().acting()) {
        clock_.run_until(clock_.now() + minutes(1));
        robot().battery_level -= 0.005;
        robot().finish_action(ActionOutcome::kSucceeded, "");
      } else {
        clock_.run_until(clock_.now() + seconds(20));
      }
    }
    EXPECT_EQ(state("C"), "succeeded");
  }
  std::vector<store::Event> robot_events(const std::string& event) const {
    std::vector<store::Event> out;
    const std::vector<store::Event> all = store::read_events(store_).value();
    for (const store::Event& e : all)
      if (e.subject == store::Subject::kRobot && e.event == event) out.push_back(e);
    return out;
  }
};

void expect_same(const BatteryRates& a, const BatteryRates& b) {
  EXPECT_EQ(a.per_metre, b.per_metre);
  EXPECT_EQ(a.moving_per_hour, b.moving_per_hour);
  EXPECT_EQ(a.acting_per_hour, b.acting_per_hour);
  EXPECT_EQ(a.idle_per_hour, b.idle_per_hour);
  EXPECT_EQ(a.charging_per_hour, b.charging_per_hour);
}

TEST(ExecutorRestore, TheBatteryEstimatorGoesOnFromWhatItLearnedBeforeAKill) {
  BatteryLife s;
  const BatteryFigures learned = s.executor().battery_figures();
  ASSERT_GE(learned.intervals_learned, 5u);  // two edges and three actions
  ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
  const BatteryFigures again = s.executor().battery_figures();
  EXPECT_EQ(again.intervals_learned, learned.intervals_learned);
  expect_same(again.learned, learned.learned);
  expect_same(again.standard_errors, learned.standard_errors);
  EXPECT_TRUE(s.robot_events("battery estimate reset").empty());
}

TEST(ExecutorRestore, AStoredBatteryEstimateThatCannotBeReadIsAWarningAndAFreshEstimator) {
  for (const std::string& stored : {std::string(R"({"version": 1, "n": oops)"), std::string(R"({"version": 9})"),
                                    std::string(R"({"version":1,"n":3,"a":[[-1,0,0,0,0],[0,1,0,0,0],[0,0,1,0,0],)"
                                                R"([0,0,0,1,0],[0,0,0,0,1]],"b":[0,0,0,0,0],"yy":0,"noise_ss":0,)"
                                                R"("noise_weight":2})")}) {
    BatteryLife s;
    ASSERT_TRUE(store::set_meta(s.store(), "exec.battery.robot", stored).ok());
    ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
    const BatteryFigures fresh = s.executor().battery_figures();
    EXPECT_EQ(fresh.intervals_learned, 0u) << stored;
    expect_same(fresh.learned, BatteryEstimator{}.rates());
    const std::vector<store::Event> reset = s.robot_events("battery estimate reset");
    ASSERT_EQ(reset.size(), 1u) << stored;
    EXPECT_EQ(reset[0].code, "battery");
    EXPECT_THAT(reset[0].reason, HasSubstr("the stored battery estimate (exec.battery.robot) could not be read"));
    EXPECT_THAT(reset[0].reason, HasSubstr("the estimator starts again from its prior"));
  }
}

}  // namespace
}  // namespace rondo::exec::testing
