// POST /api/v1/observations: a building's sensor seeing a door has the same effect as the robot's
// own sensor (the simulator's path, RobotListener::on_observation): the assumption broken, the task
// blocked and rescheduled, the events logged, the observation stored; the door seen open again
// makes the task an opportunity. Fields are checked and named; it is a write (the token).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "live_service.h"
#include "rondo/store/events.h"
#include "rondo/store/observations.h"
#include "test_files.h"

namespace rondo::test {
namespace {

// A drop at the desk of room A-120 (behind its door) in an hour's window from an hour on.
std::string drop_body(LiveService& s) {
  const Time release = s.clock().now() + hours(1);
  return fmt::format(R"({{"tasks": [{{"id": "drop-a120", "activity": "deliver a letter", "window": {{"release": "{}",
      "deadline": "{}"}}, "duration": 120, "start_node": "A-120-Desk"}}]}})",
                     format_time(release), format_time(release + hours(1)));
}

// The task's events and the schedule's, as "event/code" lines in order.
std::vector<std::string> story(LiveService& s) {
  std::vector<std::string> out;
  s.on_clock([&] {
    auto events = store::read_events(s.store());
    ASSERT_TRUE(events.ok()) << events.error().message;
    const std::vector<store::Event> all = std::move(*events);
    for (const store::Event& e : all) {
      if (e.subject == store::Subject::kTask && e.task_id == "drop-a120") out.push_back(e.event + "/" + e.code);
      if (e.subject == store::Subject::kSchedule && e.event == "rescheduled") out.push_back("schedule " + e.event + "/" + e.code);
    }
  });
  return out;
}

bool has(const std::vector<std::string>& lines, const std::string& line) {
  return std::find(lines.begin(), lines.end(), line) != lines.end();
}

bool assumes_the_door(LiveService& s) {
  bool assumed = false;
  s.on_clock([&] {
    for (const exec::Assumption& a : s.executor().assumptions())
      if (a.kind == exec::Assumption::Kind::kDoorOpen && a.what == "A-120-door" && a.task == "drop-a120") assumed = true;
  });
  return assumed;
}

struct Seen {
  std::vector<std::string> story;
  std::vector<store::Observation> stored;
};

// Submits the drop, then the door is seen closed and, a moment later, open: by `see`.
Seen door_closed_then_open(const std::string& name, const std::function<void(LiveService&, int)>& see) {
  LiveService s(fresh_dir("rondo-service-test", name), {.deployment = "examples/office/deployment.yaml"});
  auto cli = s.client();
  auto r = cli.Post("/api/v1/tasks", drop_body(s), "application/json");
  EXPECT_TRUE(r && r->status == 201) << (r ? r->body : "no answer");
  EXPECT_TRUE(eventually([&] { return assumes_the_door(s); })) << "the plan assumes A-120's door open";
  see(s, 0);
  EXPECT_TRUE(eventually([&] { return has(story(s), "blocked/assumption broken"); }));
  see(s, 1);
  EXPECT_TRUE(eventually([&] { return has(story(s), "opportunity/opportunity taken"); }));
  Seen out{.story = story(s), .stored = {}};
  s.on_clock([&] { out.stored = store::find_observations(s.store(), {.where = "A-120-door"}).value(); });
  return out;
}

TEST(ApiObservations, ABuildingObservationHasTheSameEffectAsTheRobots) {
  // The simulator's path: the robot's door sensor calls the executor as its listener.
  const Seen robot = door_closed_then_open("observe-robot", [](LiveService& s, int open) {
    s.on_clock([&] {
      s.executor().on_observation({.what = "door_open", .where = "A-120-door", .when = s.clock().now(), .value = double(open)});
    });
  });
  // The building's: POST /api/v1/observations.
  const Seen building = door_closed_then_open("observe-building", [](LiveService& s, int open) {
    auto r = s.client().Post(
        "/api/v1/observations",
        fmt::format(R"({{"kind": "door_open", "place": "A-120-door", "value": {}, "source": "door-sensor-3"}})", open),
        "application/json");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 201) << r->body;
    const Json j = body_of(r);
    EXPECT_EQ(j["observation"]["source"], "door-sensor-3");
    EXPECT_EQ(j["observation"]["value"], open);
  });
  ASSERT_FALSE(robot.story.empty());
  EXPECT_EQ(building.story, robot.story);
  for (const char* line : {"blocked/assumption broken", "schedule rescheduled/assumption broken",
                           "opportunity/opportunity taken"})
    EXPECT_TRUE(has(building.story, line)) << line;
  // Stored as the robot's are (and so learned from: the door models read every door_open), but
  // as the building's: no robot, the sensor named.
  ASSERT_EQ(building.stored.size(), 2u);
  ASSERT_EQ(robot.stored.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(building.stored[i].what, robot.stored[i].what);
    EXPECT_EQ(building.stored[i].value, robot.stored[i].value);
    EXPECT_EQ(building.stored[i].robot, "");
    EXPECT_EQ(building.stored[i].text, "from door-sensor-3");
    EXPECT_NE(robot.stored[i].robot, "");
  }
}

TEST(ApiObservations, BadFieldsAreRefusedNamingTheField) {
  LiveService s(fresh_dir("rondo-service-test", "observe-bad"), {.deployment = "examples/office/deployment.yaml"});
  auto cli = s.client();
  struct Case {
    std::string body;
    int status;
    const char* field;
    const char* says;
  };
  const std::string late = format_time(s.clock().now() + hours(2));
  const std::string old = format_time(s.clock().now() - hours(3));
  const std::vector<Case> cases = {
      {R"({"place": "A-120-door", "value": 0})", 422, "kind", "request: kind: missing"},
      {R"({"kind": "door", "place": "A-120-door", "value": 0})", 422, "kind", "'door' is not an observation kind"},
      {R"({"kind": "door_open", "place": "A-120-Desk", "value": 0})", 422, "place", "'A-120-Desk' is not a door of map"},
      {R"({"kind": "edge_blocked", "place": "nowhere", "value": 1})", 422, "place", "is not an edge of map"},
      {R"({"kind": "person_present", "place": "the-moon", "value": 1})", 422, "place", "is not a node of map"},
      {R"({"kind": "door_open", "place": "A-120-door"})", 422, "value", "request: value: missing"},
      {R"({"kind": "door_open", "place": "A-120-door", "value": 0.5})", 422, "value", "0.5 is not 1 or 0"},
      {R"({"kind": "door_open", "place": "A-120-door", "value": "shut"})", 422, "value", "is not 1 or 0"},
      {R"({"kind": "door_open", "place": "A-120-door", "value": 0, "time": "yesterday"})", 422, "time", "request: time:"},
      {R"({"kind": "door_open", "place": "A-120-door", "value": 0, "time": ")" + late + R"("})", 422, "time",
       "is after the service's clock"},
      {R"({"kind": "door_open", "place": "A-120-door", "value": 0, "time": ")" + old + R"("})", 422, "time",
       "more than an hour before"},
      {R"({"kind": "door_open", "place": "A-120-door", "value": 0, "colour": "red"})", 422, "colour", "unknown field"},
      {R"({"kind": "door_open", "place": "A-120-door", "value": 0, "source": 7})", 422, "source", "must be a string"},
  };
  for (const Case& c : cases) {
    auto r = cli.Post("/api/v1/observations", c.body, "application/json");
    ASSERT_TRUE(r) << c.body;
    EXPECT_EQ(r->status, c.status) << c.body << " -> " << r->body;
    const Json j = body_of(r);
    EXPECT_EQ(j["error"]["field"], c.field) << c.body << " -> " << r->body;
    EXPECT_NE(j["error"]["message"].get<std::string>().find(c.says), std::string::npos) << r->body;
  }
  auto malformed = cli.Post("/api/v1/observations", "{not json", "application/json");
  ASSERT_TRUE(malformed);
  EXPECT_EQ(malformed->status, 400);
  std::size_t stored = 1;
  s.on_clock([&] { stored = store::find_observations(s.store(), {.where = "A-120-door"}).value().size(); });
  EXPECT_EQ(stored, 0u) << "nothing refused is stored";
}

TEST(ApiObservations, AWriteNeedsTheToken) {
  LiveService s(fresh_dir("rondo-service-test", "observe-token"),
                {.token = "s3cret", .deployment = "examples/office/deployment.yaml"});
  auto cli = s.client();
  const std::string body = R"({"kind": "door_open", "place": "A-120-door", "value": 1})";
  auto without = cli.Post("/api/v1/observations", body, "application/json");
  ASSERT_TRUE(without);
  EXPECT_EQ(without->status, 401);
  auto with = cli.Post("/api/v1/observations", s.auth(), body, "application/json");
  ASSERT_TRUE(with);
  EXPECT_EQ(with->status, 201) << with->body;
  EXPECT_EQ(body_of(with)["observation"]["source"], "building");
}

}  // namespace
}  // namespace rondo::test
