// `rondo serve --store postgresql://...` (both as processes, on the test binary's throwaway
// cluster, tests/store/pg_cluster.h): the service keeps its store in the database, and a task that
// `rondo task add --store` queues reaches it through LISTEN/NOTIFY, long before its fallback poll
// (once a minute of wall time) could have read it.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <regex>

#include "live_service.h"
#include "rondo/store/requests.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"
#include "serve_process.h"
#include "store/pg_cluster.h"
#include "test_files.h"

namespace rondo::test {
namespace {

constexpr const char* kVisitId = "visit-waypoint2@2026-11-23T10:00";

TEST(ServePostgres, AQueuedTaskReachesTheRunningServiceByNotification) {
  std::string url;
  try {
    url = store::testing::PgCluster::get().create_database();
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
  const auto dir = fresh_dir("rondo-service-test", "serve-postgres");
  Child c = spawn({RONDO_BINARY, "serve", "--listen", "127.0.0.1:0", "--data", (dir / "data").string(), "--store",
                   url, "--speed", "10"});
  const std::string port_text = c.wait_for(std::regex(R"(on http://127\.0\.0\.1:(\d+)/)"));
  ASSERT_FALSE(port_text.empty()) << c.seen;
  EXPECT_NE(c.seen.find("store " + url), std::string::npos) << c.seen;
  EXPECT_FALSE(std::filesystem::exists(dir / "data" / "rondo.sqlite")) << "no SQLite file beside it";
  httplib::Client cli("127.0.0.1", std::stoi(port_text));
  cli.set_read_timeout(std::chrono::seconds(60));

  Child add = spawn({RONDO_BINARY, "task", "add", "urgent: come to WayPoint2 now", "--map", "examples/g4s/map.yaml",
                     "--time-zone", "Europe/London", "--at", "2026-11-23 10:00", "--store", url});
  ASSERT_EQ(add.wait_exit(), 0) << add.seen;
  ::close(add.err);
  const auto queued = std::chrono::steady_clock::now();
  // The fallback poll comes a minute after the start: seen within 10 s, the notification brought it.
  EXPECT_TRUE(eventually([&] {
    auto r = cli.Get(std::string("/api/v1/tasks/") + kVisitId);
    return r && r->status == 200;
  }, seconds(10)));
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - queued).count();
  ::testing::Test::RecordProperty("queued_to_seen_ms", std::to_string(static_cast<int>(took * 1000)));

  ASSERT_EQ(::kill(c.pid, SIGTERM), 0);
  EXPECT_EQ(c.wait_exit(), 0) << c.seen;
  ::close(c.err);
  auto db = store::Store::open(store::StoreLocation::postgres(url).value(), {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok()) << db.error().message;
  const auto requests = store::list_requests(*db);
  ASSERT_TRUE(requests.ok());
  ASSERT_EQ(requests->size(), 1u);
  EXPECT_EQ(requests->front().outcome, "added 1 task(s)");
  EXPECT_TRUE(store::get_task(*db, kVisitId).ok());
}

}  // namespace
}  // namespace rondo::test
