// rondo driving a vehicle we did not write: `rondo run --realtime --speed 10` (run_deployment)
// with a vda5050 robot, through Debian's mosquitto, against the virtual vehicle of vda-5050-lib
// 1.4.0, on the G4S example map (day_fixture.h). A short day of tasks, and the faults: a cancel
// in the middle of an edge, the vehicle killed and restarted, the broker restarted, a rejected
// order update, malformed and out-of-order states. Each asserts on the run's event log; every
// message rondo sends is validated against the official schemas by the spy. They skip, saying
// why, only when mosquitto or node (or the installed peer) is missing.
#include <gtest/gtest.h>

#include <SQLiteCpp/SQLiteCpp.h>

#include <algorithm>
#include <cmath>

#include "rondo/map/map_geometry.h"
#include "test_files.h"
#include "vda5050/day_fixture.h"

namespace rondo::vda5050::testing {
namespace {

constexpr auto kDeadline = 120s;  // generous: the machine may be busy

std::string joined(const std::vector<std::string>& lines) {
  std::string out;
  for (const std::string& l : lines) out += l + "\n";
  return out;
}

bool task_ended(const VdaDay& day, const std::string& task, const std::string& event) {
  for (const EventRow& e : day.events()) {
    if (e.task_id == task && e.event == event) return true;
  }
  return false;
}

void expect_schemas_kept(const VdaDay& day) {
  EXPECT_GT(day.spy().orders(), 0);
  EXPECT_EQ(joined(day.spy().problems()), "");
}

// Broker, vehicle and kill scenarios of seconds each: they run once, in the normal build, and not
// again under the sanitizers (the module's unit and codec tests do).
using test::kSanitized;

#define START_DAY(day)                                                                     \
  if (kSanitized) GTEST_SKIP() << "a broker and vehicle scenario: the normal build runs it"; \
  std::string why;                                                                         \
  auto day = VdaDay::start(why);                                                           \
  if (!day) GTEST_SKIP() << why;

TEST(Vda5050Day, TasksRunOnTheVehicleAndItsEdgeDurationsAreLearned) {
  START_DAY(day);
  day->run({.tasks = {{.id = "t1", .node = "WayPoint6"}, {.id = "t2", .node = "WayPoint4"},
                      {.id = "t3", .node = "WayPoint3"}},
            .run_for = "3m"});
  ASSERT_TRUE(day->wait_run_done(kDeadline));
  ASSERT_EQ(day->run_error(), "");
  for (const char* t : {"t1", "t2", "t3"}) EXPECT_TRUE(task_ended(*day, t, "succeeded")) << t << "\n" << day->event_text();
  // The traversal log holds the vehicle's real edge durations: L metres at 1 m/s take L seconds
  // on rondo's clock (the vehicle's time-lapse is rondo's speed). Never shorter than the drive
  // (less a tick); late by the state's way back, however busy the machine is.
  const std::vector<TraversalRow> log = day->traversals();
  ASSERT_GE(log.size(), 4u);
  for (const TraversalRow& t : log) {
    EXPECT_TRUE(t.success) << t.edge_id;
    const double expected = map::edge_length(day->map(), *day->map().find_edge(t.edge_id)) / kVehicleSpeed;
    const double measured = static_cast<double>(t.duration_ms) / 1000.0;
    EXPECT_GT(measured, 0.9 * expected - 0.5) << t.edge_id;
    EXPECT_LT(measured, 1.5 * expected + 4.0) << t.edge_id;
  }
  // The tasks' actions ran on the vehicle.
  EXPECT_GE(day->spy().finished_actions("noop"), 3);
  expect_schemas_kept(*day);
}

// The vehicle tells of a door in its state's information[] (the deployment maps its DOOR_STATE
// entries to door_open observations): a task in the room behind WayPoint11_WayPoint12, planned
// with that door open, is blocked and the rest rescheduled when the vehicle reports the door
// closed; when it reports the door open, the task is taken as an opportunity and done.
TEST(Vda5050Day, ADoorTheVehicleReportsClosedBreaksTheAssumptionAndOpenIsTakenAsAnOpportunity) {
  START_DAY(day);
  constexpr const char* kDoor = "WayPoint11_WayPoint12";
  const auto door_entry = [&](const char* state) {
    return Json::array({Json{{"infoType", "DOOR_STATE"},
                             {"infoLevel", "INFO"},
                             {"infoDescription", "door report"},
                             {"infoReferences", Json::array({Json{{"referenceKey", "doorId"}, {"referenceValue", kDoor}},
                                                             Json{{"referenceKey", "state"}, {"referenceValue", state}}})}}});
  };
  // The room's task opens 5 min on (rondo's clock: 30 s here), so the door is reported before
  // the vehicle could set off for it.
  day->run({.tasks = {{.id = "hall", .node = "WayPoint3"},
                      {.id = "room", .node = "WayPoint12", .release_in = std::chrono::minutes(5)}},
            .run_for = "8m",
            .robot_yaml = ", information: [{info_type: DOOR_STATE, kind: door_open, where_key: doorId, "
                          "value_key: state, values: {OPEN: 1, CLOSED: 0}}]"});
  ASSERT_TRUE(day->wait_for_event("assumptions", kDeadline, std::string("door ") + kDoor)) << day->event_text();
  ASSERT_TRUE(day->tell_information(door_entry("CLOSED"), kDeadline));
  ASSERT_TRUE(day->wait_for_event("blocked", kDeadline, std::string(kDoor) + " seen closed")) << day->event_text();
  const auto blocked = day->events_named("blocked");
  ASSERT_FALSE(blocked.empty());
  EXPECT_EQ(blocked.front().task_id, "room");
  EXPECT_EQ(blocked.front().code, "assumption broken");
  ASSERT_TRUE(day->wait_for_event("rescheduled", kDeadline, std::string(kDoor) + " seen closed")) << day->event_text();
  EXPECT_FALSE(task_ended(*day, "room", "navigating")) << day->event_text();
  ASSERT_TRUE(day->tell_information(door_entry("OPEN"), kDeadline));
  ASSERT_TRUE(day->wait_for_event("opportunity taken", kDeadline, std::string(kDoor) + " seen open"))
      << day->event_text();
  EXPECT_EQ(day->events_named("opportunity").front().task_id, "room");
  EXPECT_TRUE(day->wait_for_event("succeeded", kDeadline, "")) << day->event_text();
  ASSERT_TRUE(day->wait_run_done(kDeadline));
  ASSERT_EQ(day->run_error(), "");
  for (const char* t : {"hall", "room"}) EXPECT_TRUE(task_ended(*day, t, "succeeded")) << t << "\n" << day->event_text();
  expect_schemas_kept(*day);
}

TEST(Vda5050Day, ACancelInTheMiddleOfAnEdgeEndsOnlyWithTheVehiclesFinished) {
  START_DAY(day);
  // A navigation overrun at once: the monitor cancels the first edge while the vehicle drives it
  // (on expected values: under the chance constraint the window watch would let the journey go on).
  day->run({.tasks = {{.id = "t1", .node = "WayPoint4"}},
            .run_for = "1m",
            .executor_yaml = "{navigation_overrun: 0.01, navigation_slack: 0s, risk_alpha: null}"});
  ASSERT_TRUE(day->wait_run_done(kDeadline));
  ASSERT_EQ(day->run_error(), "");
  std::vector<EventRow> cancelled;
  for (const EventRow& e : day->events()) {
    if (e.task_id == "t1" && e.event == "edge" && e.code == "cancelled") cancelled.push_back(e);
  }
  ASSERT_EQ(cancelled.size(), 1u) << day->event_text();
  EXPECT_NE(cancelled[0].reason.find("the vehicle reported cancelOrder"), std::string::npos) << cancelled[0].reason;
  EXPECT_NE(cancelled[0].reason.find("FINISHED"), std::string::npos) << cancelled[0].reason;
  EXPECT_TRUE(day->spy().cancel_finished());
  EXPECT_TRUE(task_ended(*day, "t1", "failed")) << day->event_text();
  // A cancelled attempt says nothing about the way: not in the traversal log.
  for (const TraversalRow& t : day->traversals()) EXPECT_NE(t.edge_id, "ChargingPoint_Station");
  expect_schemas_kept(*day);
}

TEST(Vda5050Day, AKilledVehicleIsARobotFaultAndARestartedOneGoesOnFromWhereItIs) {
  START_DAY(day);
  day->run({.tasks = {{.id = "t1", .node = "WayPoint4"}, {.id = "t2", .node = "WayPoint6"}}, .run_for = "4m"});
  ASSERT_TRUE(day->wait_for_event("departed", kDeadline)) << day->event_text();
  ASSERT_TRUE(wait_until([&] { return day->spy().last_state() && day->spy().last_state()->driving; }, kDeadline));
  day->kill_vehicle();
  // Silence (or the last will) becomes a robot fault: the second one of the run, after the
  // vehicle's first appearance.
  ASSERT_TRUE(wait_until([&] { return day->events_named("fault").size() >= 2; }, kDeadline)) << day->event_text();
  const std::optional<State> last = day->spy().last_state();
  ASSERT_TRUE(last && last->agv_position);
  day->start_vehicle(last->last_node_id, last->agv_position->x, last->agv_position->y, last->agv_position->theta);
  ASSERT_TRUE(wait_until([&] { return day->events_named("ready").size() >= 2; }, kDeadline)) << day->event_text();
  ASSERT_TRUE(day->wait_run_done(kDeadline));
  ASSERT_EQ(day->run_error(), "");
  const std::vector<EventRow> events = day->events();
  // Dispatch paused: nothing departs between the fault and the vehicle's return.
  const auto fault = std::find_if(events.begin(), events.end(),
                                  [n = 0](const EventRow& e) mutable { return e.event == "fault" && ++n == 2; });
  const auto ready = std::find_if(fault, events.end(), [](const EventRow& e) { return e.event == "ready"; });
  ASSERT_NE(ready, events.end());
  EXPECT_NE(fault->reason.find("vehicle agv-7"), std::string::npos) << fault->reason;
  EXPECT_TRUE(std::none_of(fault, ready, [](const EventRow& e) { return e.code == "departed"; })) << day->event_text();
  // No edge failure learned; the day went on.
  for (const TraversalRow& t : day->traversals()) EXPECT_TRUE(t.success) << t.edge_id;
  EXPECT_TRUE(task_ended(*day, "t1", "succeeded")) << day->event_text();
  EXPECT_TRUE(task_ended(*day, "t2", "succeeded")) << day->event_text();
  expect_schemas_kept(*day);
}

// Frozen (SIGSTOP), the vehicle keeps its connection and sends nothing: no last will comes, and
// the silence past offline_after is the fault; thawed, it goes on and so does the day.
TEST(Vda5050Day, ASilentVehicleIsOfflineAfterOfflineAfterAndBackWhenItSpeaks) {
  START_DAY(day);
  day->run({.tasks = {{.id = "t1", .node = "WayPoint4"}}, .run_for = "2m"});
  ASSERT_TRUE(day->wait_for_event("departed", kDeadline)) << day->event_text();
  day->freeze_vehicle(true);
  ASSERT_TRUE(day->wait_for_event("fault", kDeadline, "no state for")) << day->event_text();
  day->freeze_vehicle(false);
  ASSERT_TRUE(wait_until([&] { return day->events_named("ready").size() >= 2; }, kDeadline)) << day->event_text();
  ASSERT_TRUE(day->wait_run_done(kDeadline));
  ASSERT_EQ(day->run_error(), "");
  for (const TraversalRow& t : day->traversals()) EXPECT_TRUE(t.success) << t.edge_id;
  EXPECT_TRUE(task_ended(*day, "t1", "succeeded")) << day->event_text();
  expect_schemas_kept(*day);
}

TEST(Vda5050Day, ABrokerRestartIsAFaultAndRondoReconnectsAndGoesOn) {
  START_DAY(day);
  day->run({.tasks = {{.id = "t1", .node = "WayPoint4"}, {.id = "t2", .node = "WayPoint6"}}, .run_for = "4m"});
  ASSERT_TRUE(day->wait_for_event("departed", kDeadline)) << day->event_text();
  ASSERT_TRUE(day->broker().restart());
  // A fault: the vehicle's last will (the broker sends it as it stops) or rondo's own lost
  // connection, whichever comes first.
  ASSERT_TRUE(wait_until([&] { return day->events_named("fault").size() >= 2; }, kDeadline)) << day->event_text();
  ASSERT_TRUE(wait_until([&] { return day->events_named("ready").size() >= 2; }, kDeadline)) << day->event_text();
  ASSERT_TRUE(day->wait_run_done(kDeadline));
  ASSERT_EQ(day->run_error(), "");
  for (const TraversalRow& t : day->traversals()) EXPECT_TRUE(t.success) << t.edge_id;
  EXPECT_TRUE(task_ended(*day, "t1", "succeeded")) << day->event_text();
  EXPECT_TRUE(task_ended(*day, "t2", "succeeded")) << day->event_text();
  expect_schemas_kept(*day);
}

TEST(Vda5050Day, ARejectedOrderUpdateAndBadStatesReachTheLogsAndTheDayGoesOn) {
  START_DAY(day);
  // A duration the vehicle cannot take (text): it rejects the update that carries the action.
  day->run({.tasks = {{.id = "t1", .node = "WayPoint6", .action_yaml = "{name: noop, args: {duration: soon}}"},
                      {.id = "t2", .node = "WayPoint4"}},
            .run_for = "3m"});
  ASSERT_TRUE(day->wait_for_event("departed", kDeadline)) << day->event_text();
  // Malformed, another vehicle's, and out of order (headerId 0 after the vehicle's later ones).
  const std::string topic = "uagv/v2/acme/agv-7/state";
  ASSERT_TRUE(wait_until([&] { return day->spy().last_state() && day->spy().last_state()->header.header_id > 2; },
                         kDeadline));
  std::string old = R"({"headerId":0,"timestamp":"2026-12-01T10:00:00.000Z","version":"2.0.0",
    "manufacturer":"acme","serialNumber":"agv-7","orderId":"","orderUpdateId":0,"lastNodeId":"WayPoint29",
    "lastNodeSequenceId":0,"nodeStates":[],"edgeStates":[],"driving":false,"operatingMode":"MANUAL",
    "actionStates":[],"batteryState":{"batteryCharge":3,"charging":false},"errors":[],
    "safetyState":{"eStop":"NONE","fieldViolation":false}})";
  std::string other = old;
  other.replace(other.find("agv-7"), 5, "agv-8");
  for (const std::string& payload : {std::string("{\"headerId\": 99, \"timestamp\": "), other, old}) {
    ASSERT_TRUE(day->spy_client().publish({.topic = topic, .payload = payload, .qos = 1, .retained = false}).ok());
  }
  ASSERT_TRUE(day->wait_run_done(kDeadline));
  ASSERT_EQ(day->run_error(), "");
  // The rejection, in the vehicle's words, is why t1 failed; t2 ran after it.
  bool rejected = false;
  for (const EventRow& e : day->events()) {
    // An update of the order that brought the vehicle there (not update 0, a new order).
    if (e.task_id == "t1" && e.reason.find("the vehicle rejected order") != std::string::npos &&
        e.reason.find("order action is not executable") != std::string::npos &&
        e.reason.find(" update 0:") == std::string::npos)
      rejected = true;
  }
  EXPECT_TRUE(rejected) << day->event_text();
  EXPECT_TRUE(task_ended(*day, "t1", "failed")) << day->event_text();
  EXPECT_TRUE(task_ended(*day, "t2", "succeeded")) << day->event_text();
  // The bad states were ignored with a reason (observations), never acted on: no MANUAL fault.
  SQLite::Database db((day->dir() / "run" / "rondo.sqlite").string(), SQLite::OPEN_READONLY);
  SQLite::Statement q(db, "SELECT note FROM observations WHERE what = 'vda5050_ignored'");
  std::vector<std::string> ignored;
  while (q.executeStep()) ignored.push_back(q.getColumn(0).getString());
  ASSERT_GE(ignored.size(), 3u) << joined(ignored);
  const std::string all = joined(ignored);
  EXPECT_NE(all.find("agv-8"), std::string::npos) << all;
  EXPECT_NE(all.find("headerId"), std::string::npos) << all;
  EXPECT_EQ(day->events_named("fault").size(), 1u) << day->event_text();  // only the start's
  expect_schemas_kept(*day);
}

}  // namespace
}  // namespace rondo::vda5050::testing
