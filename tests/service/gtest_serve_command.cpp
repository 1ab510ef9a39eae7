// `rondo serve` as a process: it serves the G4S example, and SIGTERM stops it cleanly (exit 0)
// with an event stream open and every answered task in the store.
#include <fcntl.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <regex>
#include <set>
#include <thread>
#include <vector>

#include "live_service.h"
#include "rondo/store/events.h"
#include "rondo/store/task_table.h"
#include "serve_process.h"
#include "test_files.h"

namespace rondo::test {
namespace {

TEST(ServeCommand, ServesAndStopsCleanlyOnSigterm) {
  const auto dir = fresh_dir("rondo-service-test", "process");
  std::string port_text;
  Child c = spawn_serve(dir / "data", port_text);
  ASSERT_FALSE(port_text.empty()) << c.seen;
  httplib::Client cli("127.0.0.1", std::stoi(port_text));
  cli.set_read_timeout(std::chrono::seconds(60));
  auto health = cli.Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(body_of(health)["deployment"], "g4s");
  // Routine tasks of today are there (the G4S example's routines).
  EXPECT_EQ(cli.Get("/api/v1/tasks")->status, 200);
  const Time release = std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now()) + hours(1);
  const std::string task = fmt::format(R"({{"tasks": [{{"id": "late-1", "window": {{"release": "{}", "deadline": "{}"}},
      "duration": 60, "start_node": "WayPoint2"}}]}})",
                                       format_time(release), format_time(release + hours(1)));
  auto r = cli.Post("/api/v1/tasks", task, "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;

  // An open event stream does not hold the shutdown up.
  std::atomic<bool> streaming{false};
  std::thread stream([&] {
    httplib::Client s("127.0.0.1", std::stoi(port_text));
    s.set_read_timeout(std::chrono::seconds(60));
    (void)s.Get("/api/v1/events", [&](const char*, std::size_t) {
      streaming = true;
      return true;
    });
  });
  ASSERT_TRUE(eventually([&] { return streaming.load(); }));
  ASSERT_EQ(::kill(c.pid, SIGTERM), 0);
  EXPECT_EQ(c.wait_exit(), 0) << c.seen;
  stream.join();
  c.wait_for(std::regex("(stopped)"), std::chrono::seconds(5));
  EXPECT_NE(c.seen.find("SIGTERM: stopping"), std::string::npos) << c.seen;
  ::close(c.err);
  auto db = store::Store::open(dir / "data" / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok()) << db.error().message;
  EXPECT_TRUE(store::get_task(*db, "late-1").ok());
}

// Routines added and removed through the API are in the store: after a restart the added one is
// run again and the deployment's routine that was removed stays removed.
TEST(ServeCommand, RoutinesChangedThroughTheApiSurviveARestart) {
  const auto dir = fresh_dir("rondo-service-test", "serve-routines");
  const auto names = [](httplib::Client& cli) {
    std::set<std::string> out;
    const Json list = body_of(cli.Get("/api/v1/routines"));
    for (const Json& r : list.at("routines")) out.insert(r.at("name").get<std::string>());
    return out;
  };
  for (int life = 0; life < 2; ++life) {
    std::string port_text;
    Child c = spawn_serve(dir / "data", port_text);
    ASSERT_FALSE(port_text.empty()) << c.seen;
    httplib::Client cli("127.0.0.1", std::stoi(port_text));
    cli.set_read_timeout(std::chrono::seconds(60));
    if (life == 0) {
      ASSERT_TRUE(names(cli).contains("fire-door-east"));  // the G4S deployment's
      const std::string routine = R"({"routines": [{"name": "night-round", "task": {"activity": "patrol",
          "duration": 120, "start_node": "WayPoint2"}, "window": {"from": "00:00", "to": "24:00"}}]})";
      auto added = cli.Post("/api/v1/routines", routine, "application/json");
      ASSERT_TRUE(added);
      ASSERT_EQ(added->status, 201) << added->body;
      auto removed = cli.Delete("/api/v1/routines/fire-door-east");
      ASSERT_TRUE(removed);
      ASSERT_EQ(removed->status, 200) << removed->body;
    }
    const std::set<std::string> now = names(cli);
    EXPECT_TRUE(now.contains("night-round")) << life;
    EXPECT_FALSE(now.contains("fire-door-east")) << life;
    EXPECT_TRUE(now.contains("fire-door-lab")) << life;
    ASSERT_EQ(::kill(c.pid, SIGTERM), 0);
    EXPECT_EQ(c.wait_exit(), 0) << c.seen;
    ::close(c.err);
  }
}

// Out of service through the API: stored, so a restart is still out of service; resume ends it.
TEST(ServeCommand, OutOfServiceSurvivesARestartUntilResumed) {
  const auto dir = fresh_dir("rondo-service-test", "serve-pause");
  for (int life = 0; life < 2; ++life) {
    std::string port_text;
    Child c = spawn_serve(dir / "data", port_text);
    ASSERT_FALSE(port_text.empty()) << c.seen;
    httplib::Client cli("127.0.0.1", std::stoi(port_text));
    cli.set_read_timeout(std::chrono::seconds(60));
    if (life == 0) {
      EXPECT_EQ(body_of(cli.Get("/api/v1/robot"))["out_of_service"], false);
      EXPECT_EQ(cli.Post("/api/v1/pause", R"({"halt": "yes"})", "application/json")->status, 422);
      EXPECT_EQ(cli.Post("/api/v1/pause", "{", "application/json")->status, 400);
      auto paused = cli.Post("/api/v1/pause", R"({"halt": true, "reason": "lift repair"})", "application/json");
      ASSERT_TRUE(paused);
      ASSERT_EQ(paused->status, 200) << paused->body;
      EXPECT_EQ(body_of(paused)["out_of_service"], true);
    }
    EXPECT_EQ(body_of(cli.Get("/api/v1/robot"))["out_of_service"], true) << life;
    if (life == 1) {
      auto resumed = cli.Post("/api/v1/resume", "", "application/json");
      ASSERT_TRUE(resumed);
      EXPECT_EQ(body_of(resumed)["out_of_service"], false);
      EXPECT_EQ(body_of(cli.Get("/api/v1/robot"))["out_of_service"], false);
    }
    ASSERT_EQ(::kill(c.pid, SIGTERM), 0);
    EXPECT_EQ(c.wait_exit(), 0) << c.seen;
    ::close(c.err);
  }
  auto db = store::Store::open(dir / "data" / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto events = store::read_events(*db);
  ASSERT_TRUE(events.ok());
  int out = 0, back = 0;
  for (const store::Event& e : *events) {
    out += e.event == "out of service";
    back += e.event == "back in service";
  }
  EXPECT_EQ(out, 2);  // asked, and again at the restart
  EXPECT_EQ(back, 1);
}

// SIGINT while submissions come in: the server exits 0, and every submission answered 201 before
// it went is in the store (answered after its commit).
TEST(ServeCommand, SigintWhileSubmittingLosesNoAnsweredTask) {
  const auto dir = fresh_dir("rondo-service-test", "sigint");
  std::string port_text;
  Child c = spawn_serve(dir / "data", port_text);
  ASSERT_FALSE(port_text.empty()) << c.seen;
  std::vector<std::string> answered;
  std::atomic<int> sent{0};
  std::thread client([&] {
    httplib::Client cli("127.0.0.1", std::stoi(port_text));
    cli.set_read_timeout(std::chrono::seconds(60));
    const Time release = std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now()) + hours(1);
    for (int i = 0; i < 1000; ++i) {
      const std::string id = fmt::format("burst-{}", i);
      const std::string task = fmt::format(
          R"({{"tasks": [{{"id": "{}", "window": {{"release": "{}", "deadline": "{}"}}, "duration": 60,
              "start_node": "WayPoint{}"}}]}})",
          id, format_time(release), format_time(release + hours(8)), 1 + i % 6);
      auto r = cli.Post("/api/v1/tasks", task, "application/json");
      if (!r) break;  // the server has gone
      if (r->status == 201) answered.push_back(id);
      ++sent;
    }
  });
  ASSERT_TRUE(eventually([&] { return sent.load() >= 5; }));
  ASSERT_EQ(::kill(c.pid, SIGINT), 0);
  EXPECT_EQ(c.wait_exit(), 0) << c.seen;
  client.join();
  c.wait_for(std::regex("(stopped)"), std::chrono::seconds(5));
  EXPECT_NE(c.seen.find("SIGINT: stopping"), std::string::npos) << c.seen;
  ::close(c.err);
  auto db = store::Store::open(dir / "data" / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok()) << db.error().message;
  ASSERT_GE(answered.size(), 5u);
  for (const std::string& id : answered) EXPECT_TRUE(store::get_task(*db, id).ok()) << id;
}

}  // namespace
}  // namespace rondo::test
