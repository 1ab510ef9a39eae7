// `rondo task add SENTENCE --data DIR` with `rondo serve` running on DIR (both as processes): the
// queued request is taken by the running executive and its task is seen through the API; one
// queued while the service is down is taken when it starts again.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <regex>

#include "live_service.h"
#include "rondo/store/requests.h"
#include "serve_process.h"
#include "test_files.h"

namespace rondo::test {
namespace {

// An on-demand visit has no window, so its id depends on --at only.
constexpr const char* kVisitId = "visit-waypoint2@2026-11-23T10:00";

int queue(const std::filesystem::path& data, const std::string& sentence) {
  Child c = spawn({RONDO_BINARY, "task", "add", sentence, "--map", "examples/g4s/map.yaml", "--time-zone",
                   "Europe/London", "--at", "2026-11-23 10:00", "--data", data.string()});
  const int code = c.wait_exit();
  c.wait_for(std::regex("(queued as request \\d+)"), std::chrono::seconds(5));
  EXPECT_NE(c.seen.find("queued as request"), std::string::npos) << c.seen;
  ::close(c.err);
  return code;
}

bool task_seen(httplib::Client& cli, const std::string& id) {
  auto r = cli.Get("/api/v1/tasks/" + id);
  return r && r->status == 200;
}

TEST(ServeRequests, ATaskQueuedInWordsIsTakenByTheRunningService) {
  const auto dir = fresh_dir("rondo-service-test", "serve-words");
  std::string port_text;
  Child c = spawn_serve(dir / "data", port_text);
  ASSERT_FALSE(port_text.empty()) << c.seen;
  httplib::Client cli("127.0.0.1", std::stoi(port_text));
  cli.set_read_timeout(std::chrono::seconds(60));
  EXPECT_FALSE(task_seen(cli, kVisitId));
  ASSERT_EQ(queue(dir / "data", "urgent: come to WayPoint2 now"), 0);
  EXPECT_TRUE(eventually([&] { return task_seen(cli, kVisitId); }));
  const Json task = body_of(cli.Get(std::string("/api/v1/tasks/") + kVisitId));
  EXPECT_EQ(task["source"], "words") << task.dump();
  ASSERT_EQ(::kill(c.pid, SIGTERM), 0);
  EXPECT_EQ(c.wait_exit(), 0) << c.seen;
  ::close(c.err);
  auto db = store::Store::open(dir / "data" / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto requests = store::list_requests(*db);
  ASSERT_TRUE(requests.ok());
  ASSERT_EQ(requests->size(), 1u);
  EXPECT_TRUE(requests->front().taken.has_value());
  EXPECT_EQ(requests->front().outcome, "added 1 task(s)");
}

TEST(ServeRequests, ARequestQueuedWhileTheServiceIsDownIsTakenWhenItStarts) {
  const auto dir = fresh_dir("rondo-service-test", "serve-words-restart");
  for (int life = 0; life < 2; ++life) {
    std::string port_text;
    Child c = spawn_serve(dir / "data", port_text);
    ASSERT_FALSE(port_text.empty()) << c.seen;
    httplib::Client cli("127.0.0.1", std::stoi(port_text));
    cli.set_read_timeout(std::chrono::seconds(60));
    if (life == 1) {
      EXPECT_TRUE(eventually([&] { return task_seen(cli, kVisitId); }));
    }
    ASSERT_EQ(::kill(c.pid, SIGTERM), 0);
    EXPECT_EQ(c.wait_exit(), 0) << c.seen;
    ::close(c.err);
    if (life == 0) {
      ASSERT_EQ(queue(dir / "data", "urgent: come to WayPoint2 now"), 0);
    }
  }
  auto db = store::Store::open(dir / "data" / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto waiting = store::waiting_requests(*db);
  ASSERT_TRUE(waiting.ok());
  EXPECT_TRUE(waiting->empty());
}

}  // namespace
}  // namespace rondo::test
