// The executor's behaviours of MISSION.md §3, each on a small simulated deployment with a fixed
// seed, asserted on the event log of the store (what a person would read afterwards).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "attempt_laws.h"
#include "rondo/store/observations.h"
#include "rondo/store/task_table.h"
#include "rondo/store/traversal_log.h"
#include "scenario.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

Time event_time(const Scenario& s, const std::string& id, const std::string& event) {
  for (const auto& e : s.events_of(id))
    if (e.event == event) return e.time;
  ADD_FAILURE() << id << " has no event " << event;
  return Time{};
}

std::size_t position(const std::vector<std::string>& order, const std::string& id) {
  return static_cast<std::size_t>(std::find(order.begin(), order.end(), id) - order.begin());
}

// A (30 min at the Office, must go first) and B (40 min at the Kitchen); at 08:10, while A is
// acting, someone asks for OD (5 min at the Lab). Runs until 12:00.
void on_demand_while_a_acts(Scenario& s, bool a_interruptible) {
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_tasks({task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(30), 1, a_interruptible),
                                   task("B", "Kitchen", s.at("08:00"), s.at("11:00"), minutes(40))},
                                  "test"));
  s.run_until("08:10");
  ASSERT_EQ(s.final_state("A"), "acting");
  ASSERT_TRUE(s.fleet().add_task(on_demand("OD", "Lab", minutes(5)), "request"));
  s.run_until("12:00");
}

// A task may name the robot that must do it (`robot:`): a fleet of one takes it when it names its
// own robot and refuses it, saying so, when it names another; the store records the robot.
TEST(ExecutorScenario, ATaskNamingAnotherRobotIsRefusedAndOneNamingThisRobotIsTaken) {
  Scenario s(kCalmWorld);
  s.fleet().start();
  Task elsewhere = task("R2", "Office", s.at("09:00"), s.at("10:00"), minutes(5));
  elsewhere.robot = "r2";
  const Status refused = s.fleet().add_task(elsewhere, "test");
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("robot 'r2' is not in this deployment (its robot is 'robot')"));
  Task here = task("Mine", "Office", s.at("09:00"), s.at("10:00"), minutes(5));
  here.robot = "robot";
  ASSERT_TRUE(s.fleet().add_task(here, "test"));
  s.clock().run_until(s.at("11:00"));
  EXPECT_EQ(s.final_state("Mine"), "succeeded");
  EXPECT_EQ(store::get_task(s.store(), "Mine").value().robot, "robot");
}

TEST(ExecutorScenario, OnDemandPreemptsAnInterruptibleTaskAndTheRestIsRescheduled) {
  Scenario s(kCalmWorld);
  ASSERT_NO_FATAL_FAILURE(on_demand_while_a_acts(s, /*a_interruptible=*/true));

  // The preempted task keeps its id, goes back to the queue with the reason, and is done later.
  EXPECT_EQ(s.code_of("A", "queued"), "preempted on demand");
  EXPECT_THAT(s.reason_of("A", "queued"), HasSubstr("preempted by an on-demand task: OD"));
  EXPECT_EQ(s.final_state("OD"), "succeeded");
  EXPECT_EQ(s.final_state("A"), "succeeded");
  EXPECT_EQ(s.final_state("B"), "succeeded");
  EXPECT_EQ(s.executor().tasks().count("A~1"), 0u);
  const auto acting = s.order_of("acting");
  ASSERT_EQ(std::count(acting.begin(), acting.end(), "A"), 2);
  const auto second_a = std::find(std::find(acting.begin(), acting.end(), "A") + 1, acting.end(), "A");
  EXPECT_LT(position(acting, "A"), position(acting, "OD"));
  EXPECT_LT(position(acting, "OD"), second_a - acting.begin());
  EXPECT_LT(position(acting, "OD"), position(acting, "B"));
  // The rest was planned again around the on-demand task: B moved back.
  EXPECT_THAT(s.reason_of("B", "scheduled"), HasSubstr("after preempting A"));
  EXPECT_GT(*s.executor().tasks().at("B").planned_start, s.at("08:31"));
}

TEST(ExecutorScenario, ANonInterruptibleTaskIsNotPreemptedTheOnDemandTaskRunsRightAfterIt) {
  Scenario s(kCalmWorld);
  ASSERT_NO_FATAL_FAILURE(on_demand_while_a_acts(s, /*a_interruptible=*/false));

  EXPECT_EQ(s.final_state("A"), "succeeded");
  EXPECT_THAT(s.reason_of("OD", "waits for the running task"), HasSubstr("A cannot be interrupted now"));
  EXPECT_EQ(s.final_state("OD"), "succeeded");
  EXPECT_EQ(s.final_state("B"), "succeeded");
  const auto done = s.order_of("succeeded");
  EXPECT_EQ(done, (std::vector<std::string>{"A", "OD", "B"}));
  EXPECT_EQ(s.code_of("A", "queued"), "added");  // never back in the queue
}

// Hall_Office takes 10 x its time; task A (5 min at the Office, 08:00 to 10:00) is run to 10:00
// with no navigation slack.
std::string slow_office_world() {
  return std::string(kCalmWorld) + R"(
effects:
  - name: a crowd in the corridor
    edges: [Hall_Office]
    duration_factor: 10
)";
}

void run_a_to_the_slow_office(Scenario& s) {
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("10:00"), minutes(5)), "test"));
  s.run_until("10:00");
}

TEST(ExecutorScenario, ANavigationOverrunIsPreemptedAndTheTaskFailsWithThatReason) {
  Scenario s(slow_office_world(), {.navigation_slack = Duration{0}});
  ASSERT_NO_FATAL_FAILURE(run_a_to_the_slow_office(s));

  EXPECT_EQ(s.final_state("A"), "failed");
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("navigation overrun"));
  // It was stopped at the limit (2 x 40 s expected), not when the slow edge would have ended.
  const Duration took = event_time(s, "A", "failed") - event_time(s, "A", "navigating");
  EXPECT_GE(took, seconds(79));
  EXPECT_LE(took, seconds(81));
  EXPECT_TRUE(s.order_of("acting").empty());
}

// The attempt the monitor cut is not a failure of the edge (the traversal log has no attempt of
// it) but a stopped one, kept as an observation with the seconds it had run: a lower bound of the
// edge's long attempts for the travel-time distribution (attempt_laws.h).
TEST(ExecutorScenario, AnAttemptTheNavigationMonitorCutIsKeptAsStoppedNotAsAFailure) {
  Scenario s(slow_office_world(), {.navigation_slack = Duration{0}});
  ASSERT_NO_FATAL_FAILURE(run_a_to_the_slow_office(s));

  ASSERT_EQ(s.final_state("A"), "failed");
  EXPECT_TRUE(store::find_traversals(s.store(), {.edge_id = "Hall_Office"}).value().empty());
  const auto seen = store::find_observations(s.store(), {.what = kStoppedAttempt}).value();
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].where, "Hall_Office");
  EXPECT_EQ(seen[0].text, "A");
  // It ran from its start to the cut: the journey's 80 s limit less the edges crossed before it.
  const Time cut = event_time(s, "A", "failed");
  EXPECT_NEAR(seen[0].value, to_seconds(cut - seen[0].when), 1.0);
  EXPECT_GT(seen[0].value, 0.0);
  EXPECT_LT(seen[0].value, 80.0);
}

// Under the chance constraint the stopped attempt is learned at the nightly refit: the next day
// the journey's quantile holds it, so the monitor lets the slow edge finish and the task is done.
TEST(ExecutorScenario, UnderRiskAlphaAStoppedAttemptRaisesTheNextDaysLimit) {
  // The window watch off: the journey is stopped at its limit, as without the chance constraint.
  Scenario s(slow_office_world(), {.navigation_slack = Duration{0}, .risk_alpha = 0.1, .navigation_window = false});
  ASSERT_NO_FATAL_FAILURE(run_a_to_the_slow_office(s));
  ASSERT_EQ(s.final_state("A"), "failed");
  ASSERT_EQ(store::find_observations(s.store(), {.what = kStoppedAttempt}).value().size(), 1u);

  const Time next_day = s.at("08:00") + hours(24);
  ASSERT_TRUE(s.fleet().add_task(task("B", "Office", next_day, next_day + hours(2), minutes(5)), "test"));
  s.clock().run_until(next_day + hours(2));
  EXPECT_EQ(s.final_state("B"), "succeeded");
  EXPECT_EQ(store::find_traversals(s.store(), {.edge_id = "Hall_Office"}).value().size(), 1u);
}

// The window watch (ExecutorOptions::navigation_window): under the chance constraint a journey past
// its monitor's limit goes on while the task can still start in its window. A's window (08:00 to
// 10:00) leaves the slow edge all the time it needs: A is done, and the edge's long attempt is a
// success in the traversal log, not a stopped one.
TEST(ExecutorScenario, UnderRiskAlphaAJourneyPastItsLimitGoesOnWhileTheWindowIsOpen) {
  Scenario s(slow_office_world(), {.navigation_slack = Duration{0}, .risk_alpha = 0.1});
  ASSERT_NO_FATAL_FAILURE(run_a_to_the_slow_office(s));

  EXPECT_EQ(s.final_state("A"), "succeeded");
  EXPECT_EQ(s.code_of("A", "overrun"), "window still open");
  EXPECT_THAT(s.reason_of("A", "overrun"), HasSubstr("navigation overrun: still travelling after 1m20s"));
  EXPECT_THAT(s.reason_of("A", "overrun"), HasSubstr("the task can still start in its window"));
  const auto crossed = store::find_traversals(s.store(), {.edge_id = "Hall_Office"}).value();
  ASSERT_EQ(crossed.size(), 1u);
  EXPECT_TRUE(crossed[0].success);
  EXPECT_NEAR(to_seconds(crossed[0].duration), 200.0, 1.0);
  EXPECT_TRUE(store::find_observations(s.store(), {.what = kStoppedAttempt}).value().empty());
}

// ... and is stopped when the task can no longer start in time: B must start by 08:02 (its window
// ends 08:07, 5 minutes of work), and the slow edge would bring the robot at about 08:03. The
// edge in progress ends at the Office itself, so nothing is left of the way after it: the watch
// runs to the latest start exactly.
TEST(ExecutorScenario, TheWindowWatchStopsAJourneyWhenItsTaskCanNoLongerStartInTime) {
  Scenario s(slow_office_world(), {.navigation_slack = Duration{0}, .risk_alpha = 0.1});
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_task(task("B", "Office", s.at("08:00"), s.at("08:07"), minutes(5)), "test"));
  s.run_until("09:00");

  EXPECT_EQ(s.final_state("B"), "failed");
  EXPECT_EQ(s.code_of("B", "failed"), "navigation overrun");
  EXPECT_THAT(s.reason_of("B", "failed"), HasSubstr("can no longer be expected to start in its window"));
  EXPECT_EQ(s.code_of("B", "overrun"), "window still open");
  EXPECT_EQ(event_time(s, "B", "failed"), s.at("08:02"));
  EXPECT_LT(event_time(s, "B", "overrun"), event_time(s, "B", "failed"));
  EXPECT_TRUE(s.order_of("acting").empty());
}

TEST(ExecutorScenario, AnActionOverrunIsPreemptedAndTheTaskFailsWithThatReason) {
  Scenario s(std::string(kCalmWorld) + R"(  slow: {sigma: 0, failure_probability: 0, overrun_probability: 1, overrun_factor: 3}
)",
             {.action_slack = Duration{0}});
  Task a = task("A", "Office", s.at("08:00"), s.at("10:00"), minutes(10));
  a.actions = {Action{.name = "slow", .args = {}}};
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_task(a, "test"));
  s.run_until("10:00");

  EXPECT_EQ(s.final_state("A"), "failed");
  EXPECT_THAT(s.reason_of("A", "failed"), HasSubstr("action overrun"));
  const Duration took = event_time(s, "A", "failed") - event_time(s, "A", "acting");
  EXPECT_EQ(took, minutes(15));  // 1.5 x the 10-minute processing time
}

TEST(ExecutorScenario, AnEarlyTaskWaitsForItsWindow) {
  Scenario s(kCalmWorld);
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:05"), s.at("09:00"), minutes(5)), "test"));
  s.run_until("09:00");

  EXPECT_EQ(s.final_state("A"), "succeeded");
  EXPECT_THAT(s.reason_of("A", "waiting"), HasSubstr("early: waits"));
  const Time acting = event_time(s, "A", "acting");
  EXPECT_GE(acting, s.at("08:05"));
  EXPECT_LE(acting, s.at("08:05:05"));
  EXPECT_LT(event_time(s, "A", "waiting"), event_time(s, "A", "navigating"));
}

// The store already holds a task "B" (say, from another executive on the same file): a batch that
// names it is refused whole, in the store and in memory, and the same batch without it runs.
TEST(ExecutorScenario, ABatchTheStoreRefusesLeavesNoTaskBehind) {
  Scenario s(kCalmWorld);
  ASSERT_TRUE(store::add_task(
      s.store(),
      {.id = "B", .task = Json::object(), .state = "queued", .created = s.at("07:00"), .updated = s.at("07:00")}));
  s.fleet().start();
  auto a = task("A", "Office", s.at("08:00"), s.at("10:00"), minutes(5));
  auto c = task("C", "Kitchen", s.at("08:00"), s.at("10:00"), minutes(5));
  const Status refused =
      s.fleet().add_tasks({a, task("B", "Lab", s.at("08:00"), s.at("10:00"), minutes(5)), c}, "test");
  ASSERT_FALSE(refused);
  EXPECT_THAT(refused.error().message, HasSubstr("'B' is already stored"));
  EXPECT_TRUE(s.executor().tasks().empty());
  EXPECT_TRUE(s.events_of("A").empty());
  EXPECT_TRUE(s.events_of("C").empty());

  ASSERT_TRUE(s.fleet().add_tasks({a, c}, "test"));
  s.run_until("10:00");
  EXPECT_EQ(s.final_state("A"), "succeeded");
  EXPECT_EQ(s.final_state("C"), "succeeded");
  EXPECT_EQ(s.final_state("B"), "unknown");
}

TEST(ExecutorScenario, ALateTaskFailsAndTheRestIsRescheduled) {
  Scenario s(std::string(kCalmWorld) + R"(  slow: {sigma: 0, failure_probability: 0, overrun_probability: 1, overrun_factor: 1.4}
)");
  Task a = task("A", "Office", s.at("08:00"), s.at("08:21"), minutes(20));
  a.actions = {Action{.name = "slow", .args = {}}};  // takes 28 min: inside the 30.5-min limit
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_tasks({a, task("B", "Kitchen", s.at("08:00"), s.at("08:26"), minutes(3)),
                                   task("C", "Lab", s.at("08:00"), s.at("12:00"), minutes(10))},
                                  "test"));
  s.run_until("12:00");

  EXPECT_EQ(s.final_state("A"), "succeeded");
  EXPECT_EQ(s.final_state("B"), "failed");
  EXPECT_THAT(s.reason_of("B", "failed"), HasSubstr("too late"));
  EXPECT_EQ(s.final_state("C"), "succeeded");
  EXPECT_THAT(s.reason_of("C", "scheduled"), HasSubstr("task B failed"));
}

TEST(ExecutorScenario, AnOversubscribedDayDropsTheLowestPrioritiesFirst) {
  Scenario s(kCalmWorld);
  s.fleet().start();
  std::vector<Task> tasks;
  for (int p = 1; p <= 5; ++p)
    tasks.push_back(task("P" + std::to_string(p), "Office", s.at("09:00"), s.at("10:00"), minutes(20), p));
  ASSERT_TRUE(s.fleet().add_tasks(tasks, "test"));
  s.run_until("11:00");

  // Dropped for now first, offered again while their windows can be met, then dropped for good.
  const auto for_now = s.order_of("dropped for now");
  EXPECT_EQ(std::set<std::string>(for_now.begin(), for_now.end()), (std::set<std::string>{"P1", "P2"}));
  const auto dropped = s.order_of("dropped");
  EXPECT_EQ(std::set<std::string>(dropped.begin(), dropped.end()), (std::set<std::string>{"P1", "P2"}));
  for (const char* id : {"P1", "P2"}) {
    EXPECT_FALSE(s.reason_of(id, "dropped").empty()) << id;
    EXPECT_EQ(s.code_of(id, "dropped"), "dropped for higher priority") << id;
  }
  for (const char* id : {"P3", "P4", "P5"}) EXPECT_EQ(s.final_state(id), "succeeded") << id;
}

TEST(ExecutorScenario, HigherPriorityTasksThatDoNotFitPreemptAnInterruptibleRunningTask) {
  for (const bool interruptible : {true, false}) {
    Scenario s(kCalmWorld);
    s.fleet().start();
    ASSERT_TRUE(
        s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(40), 1, interruptible), "test"));
    s.run_until("08:10");
    ASSERT_EQ(s.final_state("A"), "acting");
    ASSERT_TRUE(s.fleet().add_task(task("H", "Kitchen", s.at("08:10"), s.at("08:20"), minutes(5), 5), "test"));
    s.run_until("10:00");
    if (interruptible) {
      EXPECT_EQ(s.code_of("A", "queued"), "outranked");
      EXPECT_THAT(s.reason_of("A", "queued"), HasSubstr("outranked by new tasks"));
      EXPECT_EQ(s.final_state("H"), "succeeded");
    } else {  // MISSION.md §3: the higher-priority task is dropped after all
      EXPECT_EQ(s.final_state("A"), "succeeded");
      EXPECT_EQ(s.final_state("H"), "dropped");
      EXPECT_THAT(s.reason_of("H", "dropped"), HasSubstr("the running task A cannot be interrupted"));
    }
  }
}

// A fault in the middle of an edge: dispatch pauses, the monitors stand still, the cut attempt is
// an event and not learning data, and when the robot is ready the task goes on and completes.
TEST(ExecutorScenario, ARobotFaultMidEdgePausesDispatchAndLearnsNoEdgeFailure) {
  Scenario s(kCalmWorld, {.navigation_overrun = 2.0, .navigation_slack = seconds(10)});  // limit 90 s
  ASSERT_TRUE(s.fleet().add_task(task("a", "Office", s.at("08:00"), s.at("10:00"), minutes(2)), "test").ok());
  s.fleet().start();
  s.run_until("08:00:10");  // half-way along Dock_Hall (20 s)
  s.robot().inject_fault({.kind = RobotFault::Kind::kError, .message = "bumper pressed"});
  s.run_until("08:30");  // far past the navigation monitor's limit: it stands still
  EXPECT_TRUE(s.executor().paused());
  EXPECT_EQ(s.final_state("a"), "navigating");
  EXPECT_EQ(store::count_traversals(s.store()).value(), 0u);  // the cut attempt is not learning data
  s.robot().clear_fault();
  s.run_until("09:00");
  EXPECT_FALSE(s.executor().paused());
  EXPECT_EQ(s.final_state("a"), "succeeded");
  std::vector<std::string> robot_events;
  for (const auto& e : s.all_events())
    if (e.subject == store::Subject::kRobot) robot_events.push_back(e.event + "/" + e.code);
  // The journey home after the task is the executor's own: it says so too.
  EXPECT_EQ(robot_events, (std::vector<std::string>{"fault/robot fault", "ready/robot ready", "departed/departed",
                                                    "arrived/arrived"}));
  int cut = 0;
  for (const auto& e : s.events_of("a")) cut += e.event == "edge" && e.code == "robot fault";
  EXPECT_EQ(cut, 1);
  EXPECT_EQ(store::count_traversals(s.store()).value(), 4u);  // there and back to the dock, once each
}

TEST(ExecutorScenario, TravelEstimatesInWeekThreeAreCloserToTheTruthThanInWeekOne) {
  // Twice as slow as the map's prior says, and three times slower again at midday.
  Scenario s(R"(
kind: parametric
speed: 0.25
failure_probability: 0.02
noise: {sigma: 0.1, tail_probability: 0}
effects:
  - name: midday crowd
    all: true
    when: {from: "11:00", to: "15:00"}
    duration_factor: 3
actions:
  default: {sigma: 0, failure_probability: 0, overrun_probability: 0}
)",
             {}, "2026-11-23T00:00");
  std::vector<Routine> routines;
  for (const char* node : {"Office", "Kitchen", "Lab"}) {
    Routine r;
    r.name = std::string("visit-") + node;
    r.task = task("", node, Time{}, Time{}, minutes(5));
    r.task.window.reset();
    r.window_start = hours(8);
    r.window_end = hours(18);
    r.every = hours(1);
    routines.push_back(r);
  }
  s.fleet().add_routines(routines);
  s.fleet().start();
  s.clock().run_until(s.at("00:00") + hours(24 * 21));

  const Time start = s.at("00:00");
  const auto error_in_week = [&](int week) {
    double sum = 0;
    int n = 0;
    for (const NavigationRecord& r : s.executor().navigations()) {
      if (r.start < start + hours(24 * 7 * week) || r.start >= start + hours(24 * 7 * (week + 1))) continue;
      if (r.actual <= Duration{0}) continue;
      sum += std::abs(to_seconds(r.expected) - to_seconds(r.actual)) / to_seconds(r.actual);
      ++n;
    }
    EXPECT_GT(n, 100) << "week " << week + 1;
    return sum / n;
  };
  const double week1 = error_in_week(0), week3 = error_in_week(2);
  EXPECT_LT(week3, week1);
  // Measured 0.33 vs 0.52 until the one journey path (issue 37), 0.326 vs 0.391 since: in week 1,
  // 17 of the idle journeys home, six times slower than the map's prior at midday, are stopped by
  // the navigation monitor (`gave up`), so the robot starts more tasks away from the dock.
  EXPECT_LT(week3, 0.9 * week1) << "week 1: " << week1 << ", week 3: " << week3;
  EXPECT_LT(week3, 0.36);
  EXPECT_GE(s.fleet().refits(), 20);
}


// The calm world, with a "chat" action that cannot be interrupted for its first 10 minutes.
const std::string kChatWorld =
    std::string(kCalmWorld) + "  chat: {sigma: 0, failure_probability: 0, overrun_probability: 0, non_interruptible: 10m}\n";

TEST(ExecutorCancel, AQueuedTaskEndsCancelledAndTheRestIsRescheduled) {
  Scenario s(kCalmWorld);
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_tasks({task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(20)),
                                   task("B", "Kitchen", s.at("08:00"), s.at("10:00"), minutes(20))},
                                  "test"));
  s.run_until("08:05");
  const TaskId queued = s.final_state("A") == "queued" ? "A" : "B";
  ASSERT_EQ(s.final_state(queued), "queued");
  ASSERT_TRUE(s.executor().cancel_task(queued, "not needed today").ok());
  EXPECT_EQ(s.final_state(queued), "cancelled");
  EXPECT_EQ(s.code_of(queued, "cancelled"), "cancelled");
  EXPECT_THAT(s.reason_of(queued, "cancelled"), HasSubstr("not needed today"));
  s.run_until("10:00");
  EXPECT_EQ(s.final_state(queued == "A" ? "B" : "A"), "succeeded");
  EXPECT_EQ(s.final_state(queued), "cancelled");
  // A finished task cannot be cancelled, an unknown one is not found.
  EXPECT_EQ(s.executor().cancel_task(queued, "").error().code, ErrorCode::kConflict);
  EXPECT_EQ(s.executor().cancel_task("nobody", "").error().code, ErrorCode::kNotFound);
}

TEST(ExecutorCancel, ARunningInterruptibleTaskIsStoppedThroughTheRobot) {
  Scenario s(kCalmWorld);
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_task(task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(20)), "test"));
  s.run_until("08:00:10");  // on its way
  ASSERT_EQ(s.final_state("A"), "navigating");
  ASSERT_TRUE(s.executor().cancel_task("A", "changed my mind").ok());
  s.run_until("08:01");
  EXPECT_EQ(s.final_state("A"), "cancelled");
  // The edge the cancel cut short is an event, not learning data.
  EXPECT_EQ(s.code_of("A", "edge"), "cancelled");
  s.run_until("09:00");
  const std::vector<Traversal> log = store::find_traversals(s.store()).value();
  for (const Traversal& t : log) EXPECT_TRUE(t.success) << t.edge_id;
}

TEST(ExecutorCancel, ATaskThatCannotBeInterruptedNowIsCancelledAtItsNextInterruptibleMoment) {
  Scenario s(kChatWorld);
  s.fleet().start();
  Task a = task("A", "Office", s.at("08:00"), s.at("09:00"), minutes(20));
  a.actions = {Action{.name = "chat", .args = {}}};
  ASSERT_TRUE(s.fleet().add_task(a, "test"));
  s.run_until("08:02");  // arrived at 08:00:40, chatting: not interruptible until 08:10:40
  ASSERT_EQ(s.final_state("A"), "acting");
  ASSERT_TRUE(s.executor().cancel_task("A", "the visitor left").ok());
  EXPECT_EQ(s.final_state("A"), "acting");
  EXPECT_EQ(s.code_of("A", "cancel pending"), "cancel pending");
  s.run_until("08:30");
  EXPECT_EQ(s.final_state("A"), "cancelled");
  EXPECT_EQ(event_time(s, "A", "cancelled"), s.at("08:10:40"));
}

// A task dropped when the day is full comes back when a cancellation frees its window, and is done.
TEST(ExecutorCancel, ADroppedTaskComesBackWhenACancellationFreesItsWindow) {
  Scenario s(kCalmWorld);
  s.fleet().start();
  ASSERT_TRUE(s.fleet().add_tasks({task("Big", "Office", s.at("09:00"), s.at("10:00"), minutes(50), 5),
                                   task("Small", "Kitchen", s.at("09:00"), s.at("10:00"), minutes(30), 1)},
                                  "test"));
  s.run_until("08:30");
  ASSERT_EQ(s.code_of("Small", "dropped for now"), "dropped for higher priority");
  ASSERT_EQ(s.final_state("Small"), "queued");
  ASSERT_TRUE(s.executor().cancel_task("Big", "meeting moved").ok());
  s.run_until("11:00");
  EXPECT_FALSE(s.reason_of("Small", "re-offered").empty());
  EXPECT_EQ(s.final_state("Small"), "succeeded");
  EXPECT_EQ(s.final_state("Big"), "cancelled");
  EXPECT_TRUE(s.order_of("dropped").empty());
}

// A request the executor refuses is written to the event log, with what was wrong.
TEST(ExecutorCancel, ARejectedRequestIsAnEvent) {
  Scenario s(kCalmWorld);
  s.fleet().start();
  EXPECT_FALSE(s.fleet().add_task(task("X", "Cellar", s.at("09:00"), s.at("10:00"), minutes(5)), "api").ok());
  const auto events = s.all_events();
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.back().subject, store::Subject::kRequest);
  EXPECT_EQ(events.back().about, "X");
  EXPECT_EQ(events.back().code, "invalid request");
  EXPECT_THAT(events.back().reason, HasSubstr("Cellar"));
}

}  // namespace
}  // namespace rondo::exec::testing
