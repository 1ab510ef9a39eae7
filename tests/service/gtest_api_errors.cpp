// Every error case of the API answers {"error": {"code", "message", "field"}} with its status.
#include <arpa/inet.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include "../../src/service/api.h"
#include "live_service.h"
#include "test_files.h"

namespace rondo::test {
namespace {

void expect_error(const httplib::Result& r, int status, const std::string& code, const Json& field) {
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, status) << r->body;
  Json j = body_of(r);
  ASSERT_TRUE(j.contains("error")) << r->body;
  EXPECT_EQ(j["error"]["code"], code) << r->body;
  EXPECT_TRUE(j["error"]["message"].is_string());
  EXPECT_EQ(j["error"]["field"], field) << r->body;
}

TEST(ApiErrors, FieldPathsAreReadFromCodecMessages) {
  EXPECT_EQ(service::field_of("request: tasks[0].id: expected text, found an integer"), "tasks[0].id");
  EXPECT_EQ(service::field_of("day.yaml:7: tasks[1].window.deadline: before the release"), "tasks[1].window.deadline");
  EXPECT_EQ(service::field_of("task x: node 'B' is not on the map"), "");
  EXPECT_EQ(service::field_of("no colon at all"), "");
}

TEST(ApiErrors, MalformedJsonIs400AndTasksThatCannotBeMeantAre422NamingTheField) {
  LiveService s(fresh_dir("rondo-service-test", "errors"));
  auto cli = s.client();
  expect_error(cli.Post("/api/v1/tasks", R"({"tasks": [)", "application/json"), 400, "malformed", nullptr);
  expect_error(cli.Post("/api/v1/tasks", "[]", "application/json"), 400, "malformed", nullptr);
  const Time t = s.clock().now() + hours(1);
  const auto task = [&](const std::string& window, const std::string& rest) {
    return R"({"tasks": [{"id": "x", )" + window + ", " + rest + "}]}";
  };
  const std::string ok_window =
      fmt::format(R"("window": {{"release": "{}", "deadline": "{}"}})", format_time(t), format_time(t + hours(1)));
  const std::string backwards =
      fmt::format(R"("window": {{"release": "{}", "deadline": "{}"}})", format_time(t), format_time(t - hours(1)));
  expect_error(
      cli.Post("/api/v1/tasks", task(backwards, R"("duration": 60, "start_node": "WayPoint2")"), "application/json"),
      422, "invalid", "tasks[0].window.deadline");
  expect_error(
      cli.Post("/api/v1/tasks", task(ok_window, R"("duration": 60, "start_node": "Atlantis")"), "application/json"),
      422, "invalid", "tasks[0].start_node");
  auto too_long =
      cli.Post("/api/v1/tasks", task(ok_window, R"("duration": 7200, "start_node": "WayPoint2")"), "application/json");
  ASSERT_TRUE(too_long);
  EXPECT_EQ(too_long->status, 422);
  EXPECT_TRUE(body_of(too_long)["error"]["field"].get<std::string>().starts_with("tasks[0]")) << too_long->body;
  expect_error(cli.Post("/api/v1/tasks", task(ok_window, R"("duration": "soon", "start_node": "WayPoint2")"),
                        "application/json"),
               422, "invalid", "tasks[0].duration");
  expect_error(cli.Post("/api/v1/tasks", R"({"tasks": []})", "application/json"), 422, "invalid", "tasks");
  // Nothing of the refused requests was kept.
  EXPECT_EQ(body_of(cli.Get("/api/v1/tasks"))["total"], 0);
}

// A body that gives a key twice is refused (422, naming the field and the line), on every route that
// reads one: JSON parsers differ on which of the two wins, so no value is guessed at. Each body
// here would be taken (or answered for its task id) if the last value won.
TEST(ApiErrors, ABodyWithAKeyTwiceIs422NamingTheField) {
  LiveService s(fresh_dir("rondo-service-test", "duplicate"));
  auto cli = s.client();
  const Time t = s.clock().now() + hours(1);
  const std::string window =
      fmt::format(R"("window": {{"release": "{}", "deadline": "{}"}})", format_time(t), format_time(t + hours(1)));
  struct Case {
    std::string method;
    std::string path;
    std::string body;
    std::string field;
    std::string key;
  };
  const Case cases[] = {
      {"POST", "/api/v1/tasks", R"({"tasks": [{"id": "x", )" + window + R"(, "duration": 60,
           "duration": 120, "start_node": "WayPoint2"}]})",
       "tasks[0].duration", "duration"},
      {"POST", "/api/v1/tasks",
       R"({"tasks": [], "tasks": [{"id": "y", )" + window + R"(, "start_node": "WayPoint2"}]})", "tasks", "tasks"},
      {"PATCH", "/api/v1/tasks/nobody", R"({"priority": 1, "priority": 2})", "priority", "priority"},
      {"POST", "/api/v1/tasks/nobody/cancel", R"({"reason": "a", "reason": "b"})", "reason", "reason"},
      {"POST", "/api/v1/tasks/nobody/confirm", R"({"by": "a", "by": "b"})", "by", "by"},
      {"POST", "/api/v1/routines",
       R"({"routines": [{"name": "a", "name": "b", "task": {"duration": 120, "start_node": "WayPoint2"},
           "window": {"from": "00:00", "to": "24:00"}}]})",
       "routines[0].name", "name"},
      {"POST", "/api/v1/commands", R"({"text": "juggle", "text": "check WayPoint3 tomorrow"})", "text", "text"},
      {"POST", "/api/v1/pause", R"({"reason": "a", "reason": "b"})", "reason", "reason"},
      {"POST", "/api/v1/resume", R"({"reason": "a", "reason": "b"})", "reason", "reason"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.method + " " + c.path + " " + c.body);
    auto r = c.method == "PATCH" ? cli.Patch(c.path, c.body, "application/json")
                                 : cli.Post(c.path, c.body, "application/json");
    expect_error(r, 422, "invalid", c.field);
    if (!r) continue;
    const Json j = body_of(r);
    const std::string message = j.contains("error") ? j["error"].value("message", "") : "";
    EXPECT_TRUE(message.starts_with("request body:")) << message;
    EXPECT_NE(message.find(c.field + ": duplicate key '" + c.key + "'"), std::string::npos) << message;
  }
  // The line is the second key's.
  auto lines =
      cli.Post("/api/v1/tasks/nobody/cancel", "{\n\"reason\": \"a\",\n\n\"reason\": \"b\"}", "application/json");
  ASSERT_TRUE(lines);
  EXPECT_EQ(body_of(lines)["error"]["message"], "request body:4: reason: duplicate key 'reason'");
  // Nothing of the refused requests was kept or done.
  EXPECT_EQ(body_of(cli.Get("/api/v1/tasks"))["total"], 0);
  EXPECT_EQ(body_of(cli.Get("/api/v1/routines"))["routines"].size(), 0u);
  EXPECT_FALSE(body_of(cli.Get("/api/v1/robot"))["out_of_service"].get<bool>());
}

TEST(ApiErrors, UnknownRoutesAre404AndBodiesPastTheLimit413) {
  LiveService s(fresh_dir("rondo-service-test", "limits"), {.body_limit = 4096});
  auto cli = s.client();
  expect_error(cli.Get("/api/v1/nothing-here"), 404, "not_found", nullptr);
  expect_error(cli.Get("/api/v2/tasks"), 404, "not_found", nullptr);
  const std::string big(8192, ' ');
  auto r = cli.Post("/api/v1/tasks", big, "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
}

TEST(ApiErrors, AForeignHostHeaderIsRefused) {
  LiveService s(fresh_dir("rondo-service-test", "host"));
  auto cli = s.client();
  expect_error(cli.Get("/healthz", {{"Host", "attacker.example:80"}}), 403, "host", nullptr);
  auto ok = cli.Get("/healthz");
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->status, 200);
  EXPECT_FALSE(ok->has_header("Access-Control-Allow-Origin"));  // no CORS
}

// A client that sends half a request and stalls is disconnected after the read timeout.
TEST(ApiErrors, AStallingClientIsDisconnected) {
  LiveService s(fresh_dir("rondo-service-test", "stall"), {.read_timeout = seconds(1)});
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(fd, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<std::uint16_t>(s.port()));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
  const std::string half = fmt::format(
      "POST /api/v1/tasks HTTP/1.1\r\nHost: 127.0.0.1:{}\r\nContent-Length: 500\r\n"
      "Content-Type: application/json\r\n\r\n{{\"tasks\"",
      s.port());
  ASSERT_EQ(::send(fd, half.data(), half.size(), 0), static_cast<ssize_t>(half.size()));
  // The server answers 408 or just closes: either way the connection ends, well before the deadline.
  std::string got;
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  bool closed = false;
  while (!closed && std::chrono::steady_clock::now() < end) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    char buf[512];
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0)
      closed = true;
    else
      got.append(buf, static_cast<std::size_t>(n));
  }
  ::close(fd);
  EXPECT_TRUE(closed);
  EXPECT_TRUE(got.empty() || got.starts_with("HTTP/1.1 408") || got.starts_with("HTTP/1.1 400")) << got;
  EXPECT_EQ(body_of(s.client().Get("/api/v1/tasks"))["total"], 0);  // nothing half-added
}

}  // namespace
}  // namespace rondo::test
