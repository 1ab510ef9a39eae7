// Commands in words through the API (POST /api/v1/commands): a sentence's tasks are submitted, a
// repeated command's routines are added, a cancellation cancels what it names, and a word that is not understood is named in a 422.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <algorithm>

#include "live_service.h"
#include "request_intake.h"
#include "rondo/store/requests.h"
#include "test_files.h"

namespace rondo::test {
namespace {

TEST(ApiCommands, ASentenceAddsItsTasksAndACancellationEndsThem) {
  LiveService s(fresh_dir("rondo-service-test", "commands"));
  auto cli = s.client();
  auto added = cli.Post("/api/v1/commands", R"({"text": "check WayPoint3 tomorrow"})", "application/json");
  ASSERT_TRUE(added);
  ASSERT_EQ(added->status, 201) << added->body;
  Json j = body_of(added);
  ASSERT_EQ(j["tasks"].size(), 1u);
  EXPECT_EQ(j["tasks"][0]["start_node"], "WayPoint3");
  EXPECT_EQ(j["tasks"][0]["source"], "api");
  const std::string id = j["tasks"][0]["id"];
  EXPECT_EQ(body_of(cli.Get(("/api/v1/tasks/" + id).c_str()))["state"], "queued");

  auto cancelled = cli.Post("/api/v1/commands", R"({"text": "cancel the check of WayPoint3"})", "application/json");
  ASSERT_EQ(cancelled->status, 200) << cancelled->body;
  EXPECT_EQ(body_of(cancelled)["cancelled"], Json::array({id}));
  EXPECT_EQ(body_of(cli.Get(("/api/v1/tasks/" + id).c_str()))["state"], "cancelled");
}

TEST(ApiCommands, ARepeatedCommandAddsItsRoutineAndKeepsItStored) {
  LiveService s(fresh_dir("rondo-service-test", "commands-routine"));
  auto cli = s.client();
  auto added = cli.Post("/api/v1/commands", R"({"text": "check WayPoint3 every weekday at 09:00"})", "application/json");
  ASSERT_TRUE(added);
  ASSERT_EQ(added->status, 201) << added->body;
  Json j = body_of(added);
  ASSERT_EQ(j["routines"].size(), 1u) << j.dump();
  const std::string name = j["routines"][0]["name"];
  Json listed = body_of(cli.Get("/api/v1/routines"))["routines"];
  EXPECT_TRUE(std::any_of(listed.begin(), listed.end(), [&](const Json& r) { return r["name"] == name; }))
      << listed.dump();
  // The same routine again adds nothing: it is there already.
  auto again = cli.Post("/api/v1/commands", R"({"text": "check WayPoint3 every weekday at 09:00"})", "application/json");
  ASSERT_EQ(again->status, 200) << again->body;
  EXPECT_EQ(body_of(again)["message"], "already queued: " + name);
  EXPECT_EQ(body_of(again)["routines"][0]["name"], name);
  // Another one at the same place is a routine of its own.
  auto other = cli.Post("/api/v1/commands", R"({"text": "check WayPoint3 every weekday at 10:00"})", "application/json");
  ASSERT_EQ(other->status, 201) << other->body;
  EXPECT_EQ(body_of(other)["routines"][0]["name"], name + "~2");
}

// A person who says the same thing twice in a minute gets the task once and "already queued"
// (200) the second time, never "the id is already taken"; a different sentence that would have
// made the same id gets an id of its own.
TEST(ApiCommands, TheSameSentenceTwiceInAMinuteIsAlreadyQueuedAndAnotherNeverCollides) {
  LiveService s(fresh_dir("rondo-service-test", "commands-again"));
  auto cli = s.client();
  auto say = [&](const char* text) {
    return cli.Post("/api/v1/commands", Json{{"text", text}}.dump(), "application/json");
  };
  auto first = say("go to WayPoint3");
  ASSERT_TRUE(first);
  ASSERT_EQ(first->status, 201) << first->body;
  const std::string id = body_of(first)["tasks"][0]["id"];
  EXPECT_EQ(id, "visit-waypoint3@2026-11-25T10:00");  // the clock starts at 10:00:00: still that minute
  auto again = say("go to WayPoint3");
  ASSERT_EQ(again->status, 200) << again->body;
  const Json j = body_of(again);
  EXPECT_EQ(j["message"], "already queued: " + id);
  EXPECT_EQ(j["already_queued"], Json::array({id}));
  ASSERT_EQ(j["tasks"].size(), 1u);
  EXPECT_EQ(j["tasks"][0]["id"], id);
  EXPECT_NE(j["tasks"][0]["state"], "cancelled");  // still to do (the robot may be on its way)

  auto later = say("go to WayPoint3 before 15:00");
  ASSERT_EQ(later->status, 201) << later->body;
  EXPECT_EQ(body_of(later)["tasks"][0]["id"], id + "~2");
  EXPECT_EQ(say("go to WayPoint3 before 15:00")->status, 200);
  auto urgent = say("urgent: go to WayPoint3");
  ASSERT_EQ(urgent->status, 201) << urgent->body;
  EXPECT_EQ(body_of(urgent)["tasks"][0]["id"], id + "~3");
  // Once the first is cancelled, saying it again makes a new one.
  ASSERT_EQ(cli.Post(("/api/v1/tasks/" + id + "/cancel").c_str(), "{}", "application/json")->status, 200);
  ASSERT_TRUE(eventually([&] { return body_of(cli.Get(("/api/v1/tasks/" + id).c_str()))["state"] == "cancelled"; }));
  auto after_cancel = say("go to WayPoint3");
  ASSERT_EQ(after_cancel->status, 201) << after_cancel->body;
  EXPECT_EQ(body_of(after_cancel)["tasks"][0]["id"], id + "~4");
  // Two places, one of them asked for already: the sentence's own tasks, both new.
  auto two = say("go to WayPoint3 and WayPoint5");
  ASSERT_EQ(two->status, 201) << two->body;
  EXPECT_EQ(body_of(two)["tasks"][0]["id"], id + "~5");
  EXPECT_EQ(body_of(two)["tasks"][1]["id"], "visit-waypoint5@2026-11-25T10:00~5");
}

// A robot that says which actions it runs (a VDA 5050 vehicle's factsheet) has a task with any
// other action refused when it is submitted: 422 naming the action and the robot, in words, as a
// task, as a routine, and as a queued request (rejected with that reason).
TEST(ApiCommands, ATaskWithAnActionTheRobotCannotRunIsRefusedWhenSubmitted) {
  LiveService s(fresh_dir("rondo-service-test", "commands-actions"),
                {.robot_actions = std::vector<std::string>{"patrol", "visit"}});
  auto cli = s.client();
  const std::string cannot = "the test robot cannot run the action 'check'; it runs: patrol, visit";
  auto check = cli.Post("/api/v1/commands", R"({"text": "check WayPoint3 tomorrow"})", "application/json");
  ASSERT_EQ(check->status, 422) << check->body;
  Json e = body_of(check)["error"];
  EXPECT_EQ(e["field"], "text");
  EXPECT_NE(e["message"].get<std::string>().find(cannot), std::string::npos) << e.dump();
  EXPECT_EQ(cli.Post("/api/v1/commands", R"({"text": "patrol WayPoint3 tomorrow"})", "application/json")->status, 201);

  auto routine = cli.Post("/api/v1/commands", R"({"text": "check WayPoint3 every day"})", "application/json");
  ASSERT_EQ(routine->status, 422) << routine->body;
  EXPECT_NE(body_of(routine)["error"]["message"].get<std::string>().find("routine 'check-waypoint3': " + cannot),
            std::string::npos)
      << routine->body;

  const Time release = s.clock().now() + hours(1);
  const std::string task = fmt::format(
      R"({{"tasks": [{{"id": "door", "window": {{"release": "{}", "deadline": "{}"}}, "duration": 60,
          "start_node": "WayPoint2", "actions": ["check"]}}]}})",
      format_time(release), format_time(release + hours(2)));
  auto posted = cli.Post("/api/v1/tasks", task, "application/json");
  ASSERT_EQ(posted->status, 422) << posted->body;
  EXPECT_NE(posted->body.find("task door: " + cannot), std::string::npos) << posted->body;

  // The same task queued in the store (as `rondo task add --data` queues it): rejected when taken.
  std::vector<store::RequestRow> rows;
  s.on_clock([&] {
    Json body = Json::parse(task);
    body["timezone"] = "UTC";
    ASSERT_TRUE(store::queue_request(s.store(), {.queued = s.clock().now(), .source = "words", .sentence = "check",
                                                 .body = body})
                    .ok());
    app::RequestIntake intake(s.clock(), s.fleet(), s.store());
    ASSERT_TRUE(intake.take_waiting().ok());
    rows = store::list_requests(s.store()).value();
  });
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].outcome, "rejected: task door: " + cannot);
}

// With the deployment's places file (examples/office: places.yaml), rooms and their aliases are
// understood; without one ("check the kitchen" on G4S) only node names are.
TEST(ApiCommands, TheDeploymentsPlacesFileNamesRoomsByTheirAliases) {
  LiveService s(fresh_dir("rondo-service-test", "commands-places"), {.deployment = "examples/office/deployment.yaml"});
  auto cli = s.client();
  auto added = cli.Post("/api/v1/commands", R"({"text": "check the kitchen tomorrow"})", "application/json");
  ASSERT_EQ(added->status, 201) << added->body;
  EXPECT_EQ(body_of(added)["tasks"][0]["start_node"], "A-117");
  LiveService g4s(fresh_dir("rondo-service-test", "commands-no-places"));
  EXPECT_EQ(g4s.client().Post("/api/v1/commands", R"({"text": "check the kitchen tomorrow"})", "application/json")->status,
            422);
}

TEST(ApiCommands, AWordOrPlaceNotUnderstoodIsNamed) {
  LiveService s(fresh_dir("rondo-service-test", "commands-bad"));
  auto cli = s.client();
  auto moon = cli.Post("/api/v1/commands", R"({"text": "check the moon"})", "application/json");
  ASSERT_EQ(moon->status, 422);
  Json e = body_of(moon)["error"];
  EXPECT_EQ(e["field"], "text");
  EXPECT_NE(e["message"].get<std::string>().find("no place called 'the moon'"), std::string::npos) << e.dump();
  auto odd = cli.Post("/api/v1/commands", R"({"text": "juggle WayPoint3"})", "application/json");
  ASSERT_EQ(odd->status, 422);
  EXPECT_NE(body_of(odd)["error"]["message"].get<std::string>().find("juggle"), std::string::npos)
      << body_of(odd).dump();
  EXPECT_EQ(cli.Post("/api/v1/commands", "{", "application/json")->status, 400);
  EXPECT_EQ(cli.Post("/api/v1/commands", R"({"words": "check WayPoint3"})", "application/json")->status, 422);
  EXPECT_EQ(cli.Post("/api/v1/commands", R"({"text": 3})", "application/json")->status, 422);
}

}  // namespace
}  // namespace rondo::test
