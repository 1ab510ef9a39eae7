// `rondo task add SENTENCE --data DIR` with `rondo serve` running on DIR (both as processes): the
// queued request is taken by the running executive and its task is seen through the API; one
// queued while the service is down is taken when it starts again; a routine queued in words is
// added as POST /api/v1/routines adds it, kept over a restart, and the same one again is already
// queued.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <regex>

#include "live_service.h"
#include "rondo/store/events.h"
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

// How many of the service's routines are called `name`.
int routines_named(httplib::Client& cli, const std::string& name) {
  auto r = cli.Get("/api/v1/routines");
  if (!r || r->status != 200) return -1;
  int n = 0;
  const Json body = body_of(r);
  for (const Json& routine : body["routines"])
    if (routine.value("name", "") == name) ++n;
  return n;
}

std::vector<store::RequestRow> requests_of(const std::filesystem::path& data) {
  auto db = store::Store::open(data / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  if (!db) return {};
  auto rows = store::list_requests(*db);
  return rows ? *rows : std::vector<store::RequestRow>{};
}

TEST(ServeRequests, ARoutineQueuedInWordsIsAddedKeptOverARestartAndNotTwice) {
  const auto dir = fresh_dir("rondo-service-test", "serve-routine");
  const std::string sentence = "check WayPoint2 every 2 hours";
  for (int life = 0; life < 2; ++life) {
    std::string port_text;
    Child c = spawn_serve(dir / "data", port_text);
    ASSERT_FALSE(port_text.empty()) << c.seen;
    httplib::Client cli("127.0.0.1", std::stoi(port_text));
    cli.set_read_timeout(std::chrono::seconds(60));
    if (life == 0) {
      EXPECT_EQ(routines_named(cli, "check-waypoint2"), 0);
      ASSERT_EQ(queue(dir / "data", sentence), 0);
      EXPECT_TRUE(eventually([&] { return routines_named(cli, "check-waypoint2") == 1; }));
      // The same routine again: already queued, nothing added, and the service runs on.
      ASSERT_EQ(queue(dir / "data", sentence), 0);
      EXPECT_TRUE(eventually([&] {
        const auto rows = requests_of(dir / "data");
        return rows.size() == 2 && rows[1].taken.has_value();
      }));
    }
    EXPECT_EQ(routines_named(cli, "check-waypoint2"), 1) << "life " << life;
    ASSERT_EQ(::kill(c.pid, SIGTERM), 0);
    EXPECT_EQ(c.wait_exit(), 0) << c.seen;
    ::close(c.err);
  }
  const auto rows = requests_of(dir / "data");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].outcome, "added 1 routine(s): check-waypoint2");
  EXPECT_EQ(rows[1].outcome, "already queued: check-waypoint2");
  auto db = store::Store::open(dir / "data" / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok()) << db.error().message;
  int added = 0;
  int rejected = 0;
  auto events = store::read_events(*db);
  ASSERT_TRUE(events.ok());
  for (const store::Event& e : *events) {
    if (e.subject != store::Subject::kRequest) continue;
    if (e.event == "routines added") ++added;
    if (e.event == "rejected") ++rejected;
  }
  EXPECT_EQ(added, 1);
  EXPECT_EQ(rejected, 0);
}

}  // namespace
}  // namespace rondo::test
