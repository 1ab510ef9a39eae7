// Commands in words through the API (POST /api/v1/commands): a sentence's tasks are submitted, a
// repeated command's routines are added, a cancellation cancels what it names, and a word that is not understood is named in a 422.
#include <gtest/gtest.h>

#include <algorithm>

#include "live_service.h"
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
  // The same routine again is refused, naming the field of the sentence.
  auto again = cli.Post("/api/v1/commands", R"({"text": "check WayPoint3 every weekday at 09:00"})", "application/json");
  ASSERT_EQ(again->status, 422) << again->body;
  EXPECT_EQ(body_of(again)["error"]["field"], "text");
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
