// The read views (robot, map, schedule, an edge's model), routines, /healthz, /metrics, and the
// OpenAPI document against the routes the server really answers.
#include <gtest/gtest.h>

#include <regex>
#include <set>

#include "live_service.h"
#include "rondo/store/robot_state.h"
#include "test_files.h"

namespace rondo::test {
namespace {

TEST(ApiViews, RobotMapScheduleAndEdgeModel) {
  LiveService s(fresh_dir("rondo-service-test", "views"));
  auto cli = s.client();
  ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("v1", hours(1)), "application/json")->status, 201);

  Json robot = body_of(cli.Get("/api/v1/robot"));
  EXPECT_EQ(robot["node"], "ChargingPoint");
  EXPECT_TRUE(robot["pose"]["x"].is_number());
  EXPECT_TRUE(robot["phase"].is_string());
  EXPECT_GE(robot["battery"].get<double>(), 0.0);
  EXPECT_LE(robot["battery"].get<double>(), 1.0);
  EXPECT_TRUE(robot["faults"].is_array());

  Json map = body_of(cli.Get("/api/v1/map"));
  ASSERT_TRUE(map.contains("nodes")) << map.dump().substr(0, 200);
  EXPECT_EQ(map["nodes"].size(), s.map().node_count());

  Json day = body_of(cli.Get("/api/v1/schedule"));
  bool found = false;
  for (const Json& t : day["tasks"])
    if (t["id"] == "v1") {
      found = true;
      EXPECT_TRUE(t["planned"]["start"].is_string());
      EXPECT_TRUE(t["actual"]["start"].is_null());
    }
  EXPECT_TRUE(found) << day.dump();
  EXPECT_EQ(day["planned_order"], Json::array({"v1"}));
  EXPECT_EQ(cli.Get("/api/v1/schedule?date=tomorrow")->status, 422);

  const std::string edge = s.map().edges()[0].id;
  auto model = cli.Get(("/api/v1/edges/" + edge + "/model?step_minutes=60").c_str());
  ASSERT_EQ(model->status, 200) << model->body;
  Json m = body_of(model);
  ASSERT_EQ(m["points"].size(), 24u);
  for (const Json& p : m["points"]) {
    EXPECT_GE(p["p"].get<double>(), 0.0);
    EXPECT_LE(p["p"].get<double>(), 1.0);
    EXPECT_GT(p["expected_s"].get<double>(), 0.0);
  }
  EXPECT_EQ(m["model"], "prior");  // nothing learned yet
  EXPECT_EQ(cli.Get("/api/v1/edges/no-such-edge/model")->status, 404);
  EXPECT_EQ(cli.Get(("/api/v1/edges/" + edge + "/model?step_minutes=0").c_str())->status, 422);
}

TEST(ApiViews, RoutinesAreListedAddedAndRemovedWhileRunning) {
  LiveService s(fresh_dir("rondo-service-test", "routines"));
  auto cli = s.client();
  EXPECT_EQ(body_of(cli.Get("/api/v1/routines"))["routines"].size(), 0u);
  const std::string routine = R"({"routines": [{"name": "night-round", "task": {"activity": "patrol",
      "duration": 120, "start_node": "WayPoint2"}, "window": {"from": "00:00", "to": "24:00"}}]})";
  auto added = cli.Post("/api/v1/routines", routine, "application/json");
  ASSERT_EQ(added->status, 201) << added->body;
  Json list = body_of(cli.Get("/api/v1/routines"));
  ASSERT_EQ(list["routines"].size(), 1u);
  EXPECT_EQ(list["routines"][0]["name"], "night-round");
  // Today's instance was added at once (its window lasts until midnight UTC; in the last minutes
  // of the day it can no longer be met, and none is made).
  const Time now = s.clock().now();
  const Duration into_day = now - std::chrono::floor<std::chrono::days>(now);
  Json made = body_of(cli.Get("/api/v1/tasks?source=routine"));
  if (into_day < hours(23) + minutes(50)) {
    ASSERT_EQ(made["total"], 1) << made.dump();
    EXPECT_TRUE(made["tasks"][0]["id"].get<std::string>().starts_with("night-round@"));
  }
  EXPECT_EQ(cli.Post("/api/v1/routines", routine, "application/json")->status, 422);  // the name is taken
  auto bad = cli.Post("/api/v1/routines",
                      R"({"routines": [{"name": "r", "task": {"duration": 60, "start_node": "Atlantis"},
                          "window": {"from": "09:00", "to": "10:00"}}]})",
                      "application/json");
  EXPECT_EQ(bad->status, 422);
  EXPECT_EQ(body_of(bad)["error"]["field"], "routines[0].task.start_node") << bad->body;
  EXPECT_EQ(cli.Delete("/api/v1/routines/night-round")->status, 200);
  EXPECT_EQ(body_of(cli.Get("/api/v1/routines"))["routines"].size(), 0u);
  EXPECT_EQ(cli.Delete("/api/v1/routines/night-round")->status, 404);
}

TEST(ApiViews, HealthAndMetrics) {
  LiveService s(fresh_dir("rondo-service-test", "metrics"));
  auto cli = s.client();
  Json h = body_of(cli.Get("/healthz"));
  EXPECT_EQ(h["status"], "ok");
  ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("m1"), "application/json")->status, 201);
  auto m = cli.Get("/metrics");
  ASSERT_EQ(m->status, 200);
  EXPECT_TRUE(m->get_header_value("Content-Type").starts_with("text/plain"));
  EXPECT_NE(m->body.find("rondo_tasks{state=\"queued\"} 1\n"), std::string::npos) << m->body;
  EXPECT_NE(m->body.find("rondo_schedule_calls_total "), std::string::npos);
  EXPECT_NE(m->body.find("rondo_robot_battery "), std::string::npos);
  // What the process holds: SQLite's share is above zero once a store is open.
  const std::smatch sqlite = [&] {
    std::smatch found;
    std::regex_search(m->body, found, std::regex("\nrondo_memory_sqlite_bytes ([0-9]+)\n"));
    return found;
  }();
  ASSERT_FALSE(sqlite.empty()) << m->body;
  EXPECT_GT(std::stoll(sqlite[1].str()), 0);
  EXPECT_NE(m->body.find("rondo_http_requests_total{route=\"POST /api/v1/tasks\",status=\"201\"} 1\n"),
            std::string::npos)
      << m->body;
  EXPECT_NE(m->body.find("rondo_http_request_seconds_count{route=\"POST /api/v1/tasks\"} 1\n"), std::string::npos);
}

// Every route the server answers is in the OpenAPI document, and every operation in the document
// is answered by a route (not by the unknown-route 404).
TEST(ApiViews, TheOpenApiDocumentListsExactlyTheRoutes) {
  LiveService s(fresh_dir("rondo-service-test", "openapi"));
  auto cli = s.client();
  auto r = cli.Get("/api/v1/openapi.json");
  ASSERT_EQ(r->status, 200);
  Json doc = body_of(r);
  EXPECT_EQ(doc["openapi"].get<std::string>().substr(0, 2), "3.");
  std::set<std::pair<std::string, std::string>> documented, served;
  for (const auto& [path, ops] : doc["paths"].items())
    for (const auto& [method, op] : ops.items()) {
      std::string m = method;
      std::transform(m.begin(), m.end(), m.begin(), [](char c) { return static_cast<char>(std::toupper(c)); });
      documented.insert({m, path});
      EXPECT_TRUE(op.contains("summary") && op.contains("responses")) << method << " " << path;
    }
  for (const service::EndpointInfo& route : s.server().endpoints()) served.insert({route.method, route.path});
  EXPECT_EQ(documented, served);
  for (const auto& [method, path] : documented) {
    if (path == "/api/v1/events") continue;  // a stream; its own test reads it
    const std::string concrete = std::regex_replace(path, std::regex(R"(\{[a-z_]+\})"), "x");
    httplib::Result res = method == "GET"     ? cli.Get(concrete.c_str())
                          : method == "POST"  ? cli.Post(concrete.c_str(), "{}", "application/json")
                          : method == "PATCH" ? cli.Patch(concrete.c_str(), "{}", "application/json")
                                              : cli.Delete(concrete.c_str());
    ASSERT_TRUE(res) << method << " " << concrete;
    const Json j = Json::parse(res->body, nullptr, false);
    const bool unknown_route = res->status == 404 && !j.is_discarded() && j.contains("error") &&
                               j["error"]["message"].get<std::string>().starts_with("no route");
    EXPECT_FALSE(unknown_route) << method << " " << concrete;
  }
}

}  // namespace
}  // namespace rondo::test

namespace rondo::test {
namespace {

TEST(ApiViews, EveryEdgeNowAndTheEventTail) {
  LiveService s(fresh_dir("rondo-service-test", "edges"));
  auto cli = s.client();
  Json e = body_of(cli.Get("/api/v1/edges"));
  ASSERT_EQ(e["edges"].size(), s.map().edge_count());
  for (const Json& edge : e["edges"]) {
    EXPECT_GE(edge["p"].get<double>(), 0.0);
    EXPECT_LE(edge["p"].get<double>(), 1.0);
  }
  EXPECT_EQ(cli.Get("/api/v1/edges?at=noon")->status, 422);
  for (int i = 0; i < 3; ++i)
    ASSERT_EQ(
        cli.Post("/api/v1/tasks", s.task_body("tail" + std::to_string(i), hours(1 + i)), "application/json")->status,
        201);
  // ?tail=1 starts with the log's last event only.
  std::string got;
  (void)cli.Get("/api/v1/events?tail=1", [&](const char* data, std::size_t n) {
    got.append(data, n);
    return got.find("\n\n") == std::string::npos;
  });
  // The last event: tail2's last one, or a schedule event after it (what the schedule assumes).
  Json last = body_of(cli.Get("/api/v1/tasks/tail2"));
  const std::int64_t last_seq = last["events"].back()["seq"];
  ASSERT_TRUE(got.starts_with("id: ")) << got;
  const std::int64_t first_id = std::stoll(got.substr(4));
  EXPECT_GE(first_id, last_seq) << got;
  EXPECT_EQ(got.find("\nid: "), std::string::npos) << "one event only: " << got;
  EXPECT_EQ(cli.Get("/api/v1/events?tail=-1")->status, 422);
}

TEST(ApiViews, TheDashboardIsServedFromTheBinaryWithoutTheToken) {
  LiveService s(fresh_dir("rondo-service-test", "dashboard"), {.token = "dashboard-token-0123456789"});
  auto cli = s.client();
  auto page = cli.Get("/");
  ASSERT_EQ(page->status, 200);
  EXPECT_TRUE(page->get_header_value("Content-Type").starts_with("text/html"));
  EXPECT_NE(page->body.find("<script src=\"/dashboard.js\"></script>"), std::string::npos);
  EXPECT_NE(page->get_header_value("Content-Security-Policy").find("default-src 'self'"), std::string::npos);
  auto script = cli.Get("/dashboard.js");
  ASSERT_EQ(script->status, 200);
  EXPECT_TRUE(script->get_header_value("Content-Type").starts_with("text/javascript"));
  EXPECT_NE(script->body.find("sessionStorage"), std::string::npos);  // asks for the token, keeps it in the tab
  EXPECT_EQ(cli.Get("/dashboard.css")->status, 200);
  for (const auto* body : {&page->body, &script->body}) EXPECT_EQ(body->find("dashboard-token"), std::string::npos);
}

// A fleet's robots (issue 38): listed, one by name (404 for another), and paused one at a time:
// the pause is stored under the robot's own key, and the others keep working.
TEST(ApiViews, TheFleetsRobotsAreListedAndPausedOneByOne) {
  LiveService s(fresh_dir("rondo-service-test", "robots"), {.more_robots = {"r2", "r3"}});
  auto cli = s.client();
  Json all = body_of(cli.Get("/api/v1/robots"));
  ASSERT_EQ(all["robots"].size(), 3u) << all.dump();
  EXPECT_EQ(all["robots"][0]["name"], "robot");
  EXPECT_EQ(all["robots"][1]["name"], "r2");
  EXPECT_EQ(all["robots"][2]["node"], "ChargingPoint");
  EXPECT_EQ(all["robots"][2]["open_tasks"], 0);
  ASSERT_EQ(cli.Post("/api/v1/tasks", s.task_body("f1", hours(1)), "application/json")->status, 201);
  int open = 0;
  long queued = 0;
  std::string holder;
  const Json now = body_of(cli.Get("/api/v1/robots"));
  for (const Json& r : now["robots"]) {
    open += r["open_tasks"].get<int>();
    // The stored tasks by state (the dashboard's totals) agree with the open ones.
    ASSERT_TRUE(r["tasks"].is_object()) << r.dump();
    for (const auto& [state, n] : r["tasks"].items()) {
      if (state == "queued") queued += n.get<long>();
      holder = r["name"];
    }
  }
  EXPECT_EQ(open, 1) << now.dump();
  EXPECT_EQ(queued, 1) << now.dump();
  // The day's schedule names each task's robot, and gives every robot its lane.
  const Json day = body_of(cli.Get("/api/v1/schedule"));
  ASSERT_EQ(day["robots"].size(), 3u) << day.dump();
  EXPECT_EQ(day["robots"][1]["name"], "r2");
  for (const Json& t : day["tasks"]) {
    if (t["id"] == "f1") {
      EXPECT_EQ(t["robot"], holder) << day.dump();
    }
  }
  // The task and its events carry the robot too.
  const Json f1 = body_of(cli.Get("/api/v1/tasks/f1"));
  EXPECT_EQ(f1["robot"], holder) << f1.dump();
  ASSERT_FALSE(f1["events"].empty()) << f1.dump();
  EXPECT_EQ(f1["events"].back()["robot"], holder) << f1.dump();

  Json r2 = body_of(cli.Get("/api/v1/robots/r2"));
  EXPECT_EQ(r2["name"], "r2");
  EXPECT_FALSE(r2["out_of_service"].get<bool>());
  EXPECT_EQ(cli.Get("/api/v1/robots/r9")->status, 404);

  auto paused = cli.Post("/api/v1/robots/r2/pause", R"({"reason": "wheel check"})", "application/json");
  ASSERT_EQ(paused->status, 200) << paused->body;
  EXPECT_EQ(body_of(paused)["robot"], "r2");
  EXPECT_TRUE(body_of(cli.Get("/api/v1/robots/r2"))["out_of_service"].get<bool>());
  EXPECT_FALSE(body_of(cli.Get("/api/v1/robots/r3"))["out_of_service"].get<bool>());
  EXPECT_FALSE(body_of(cli.Get("/api/v1/robot"))["out_of_service"].get<bool>());
  std::optional<std::string> stored;
  s.on_clock([&] { stored = store::get_meta(s.store(), "serve.out_of_service.r2").value(); });
  EXPECT_EQ(stored, "1");
  EXPECT_EQ(cli.Post("/api/v1/robots/r9/pause", "", "application/json")->status, 404);
  ASSERT_EQ(cli.Post("/api/v1/robots/r2/resume", "", "application/json")->status, 200);
  EXPECT_FALSE(body_of(cli.Get("/api/v1/robots/r2"))["out_of_service"].get<bool>());
}

}  // namespace
}  // namespace rondo::test
