// The lease of the active executive and the fencing of its writes (rondo/store/lease.h), on the
// throwaway PostgreSQL cluster: one holder at a time, each new one at a higher epoch, a frozen
// holder cut off once its renewal is stale, and a store that carries an older epoch refused by the
// database itself. SQLite has no lease.
#include <gtest/gtest.h>

#include <chrono>

#include "rondo/store/events.h"
#include "rondo/store/lease.h"
#include "rondo/store/requests.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"
#include "store/pg_cluster.h"
#include "store/temp_db.h"

namespace rondo::store {
namespace {

using testing::PgCluster;
using testing::run_sql;

Time at(int s) {
  return Time{seconds(s)};
}

TaskRow row(const std::string& id, int s) {
  return TaskRow{.id = id, .task = Json{{"id", id}}, .state = "queued", .created = at(s), .updated = at(s)};
}

class LeasePostgres : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      url_ = PgCluster::get().create_database();
    } catch (const std::exception& e) {
      FAIL() << e.what();
    }
    auto made = Store::open(location());  // makes the schema, lease row included
    ASSERT_TRUE(made.ok()) << made.error().message;
  }
  StoreLocation location() const { return StoreLocation::postgres(url_).value(); }
  Store open() const {
    auto s = Store::open(location());
    EXPECT_TRUE(s.ok()) << s.error().message;
    return std::move(s).value();
  }
  Lease lease(const std::string& holder) const {
    auto l = Lease::connect(location(), holder);
    EXPECT_TRUE(l.ok()) << l.error().message;
    return std::move(l).value();
  }
  std::string url_;
};

TEST_F(LeasePostgres, OneHolderAtATimeEachAtANewEpoch) {
  Lease a = lease("holder-a");
  Lease b = lease("holder-b");
  auto first = a.try_take(seconds(30));
  ASSERT_TRUE(first.ok()) << first.error().message;
  ASSERT_EQ(*first, std::optional<std::int64_t>{1});
  auto again = a.try_take(seconds(30));
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(*again, std::optional<std::int64_t>{1}) << "held already: the same epoch";
  auto other = b.try_take(seconds(30));
  ASSERT_TRUE(other.ok()) << other.error().message;
  EXPECT_FALSE(other->has_value()) << "a live holder keeps it";
  EXPECT_TRUE(a.renew().ok());

  Store db = open();
  auto state = read_lease(db);
  ASSERT_TRUE(state.ok()) << state.error().message;
  EXPECT_EQ(state->epoch, 1);
  EXPECT_EQ(state->holder, "holder-a");
  EXPECT_GE(state->age.count(), 0);

  a.release();  // a clean stop: the next one takes it at once
  auto second = b.try_take(seconds(30));
  ASSERT_TRUE(second.ok()) << second.error().message;
  EXPECT_EQ(*second, std::optional<std::int64_t>{2});
  const Status lost = a.renew();
  ASSERT_FALSE(lost.ok());
  EXPECT_NE(lost.error().message.find("not held"), std::string::npos) << lost.error().message;
  EXPECT_EQ(read_lease(db)->holder, "holder-b");
}

TEST_F(LeasePostgres, TheDatabaseRefusesTheWritesOfAStaleEpoch) {
  Lease a = lease("holder-a");
  ASSERT_EQ(a.try_take(seconds(30)).value(), std::optional<std::int64_t>{1});
  Store old_active = open();
  ASSERT_TRUE(fence_writes(old_active, 1, "holder-a-store").ok());
  ASSERT_TRUE(add_task(old_active, row("t1", 1), "added").ok());

  // A newer active: epoch 2 (the old one's process is frozen, say; its store connection lives on).
  a.release();
  Lease b = lease("holder-b");
  ASSERT_EQ(b.try_take(seconds(30)).value(), std::optional<std::int64_t>{2});
  Store new_active = open();
  ASSERT_TRUE(fence_writes(new_active, 2, "holder-b").ok());

  // Every kind of write of the old one is refused, by the database: rondo's own code has no check.
  const Status task = add_task(old_active, row("t2", 2), "added");
  ASSERT_FALSE(task.ok());
  EXPECT_EQ(task.error().code, ErrorCode::kConflict);
  EXPECT_NE(task.error().message.find("stale epoch 1: the lease is at epoch 2"), std::string::npos)
      << task.error().message;
  EXPECT_FALSE(set_task_state(old_active, "t1", "failed", at(3), "x").ok());
  EXPECT_FALSE(append_event(old_active, {.time = at(3), .subject = Subject::kRobot, .about = "r", .event = "fault"}).ok());
  EXPECT_FALSE(set_meta(old_active, "k", "v").ok());
  EXPECT_FALSE(save_robot_state(old_active, {.robot = "r", .node = "A", .updated = at(3)}).ok());

  // The new one writes; so do tools that carry no epoch (rondo task add queues a request).
  EXPECT_TRUE(add_task(new_active, row("t3", 4), "added").ok());
  Store tool = open();
  EXPECT_TRUE(queue_request(tool, {.queued = at(5), .source = "words", .body = Json::object()}).ok());
  EXPECT_TRUE(get_task(new_active, "t1").ok());
  EXPECT_EQ(get_task(new_active, "t1")->state, "queued") << "the refused update left no trace";
  EXPECT_FALSE(get_task(new_active, "t2").ok());

  // Each event records the epoch it was written under.
  EXPECT_EQ(run_sql(url_, "DO $$ BEGIN IF (SELECT string_agg(task_id || ':' || epoch, ',' ORDER BY seq) FROM events) "
                          "<> 't1:1,t3:2' THEN RAISE EXCEPTION 'epochs: %', (SELECT string_agg(task_id || ':' || "
                          "epoch, ',' ORDER BY seq) FROM events); END IF; END $$"),
            "");
}

TEST_F(LeasePostgres, AFrozenHolderIsCutOffOnceItsRenewalIsStale) {
  Lease a = lease("holder-a");
  ASSERT_EQ(a.try_take(seconds(30)).value(), std::optional<std::int64_t>{1});
  Store a_store = open();
  ASSERT_TRUE(fence_writes(a_store, 1, "holder-a").ok());
  Lease b = lease("holder-b");
  // Renewed within 30 s: b waits. Stale after 0 ms: the holder's sessions are ended, and a later
  // try takes it (each try is a round trip to the server; no waiting in between).
  ASSERT_FALSE(b.try_take(seconds(30)).value().has_value());
  std::optional<std::int64_t> taken;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (!taken && std::chrono::steady_clock::now() < deadline) {
    auto t = b.try_take(Duration{0});
    ASSERT_TRUE(t.ok()) << t.error().message;
    taken = *t;
  }
  ASSERT_EQ(taken, std::optional<std::int64_t>{2});
  // The frozen one wakes up: its lease and its store connection are gone.
  EXPECT_FALSE(a.renew().ok());
  EXPECT_FALSE(add_task(a_store, row("late", 1), "added").ok());
  Store db = open();
  EXPECT_FALSE(get_task(db, "late").ok());
  EXPECT_EQ(read_lease(db)->epoch, 2);
}

TEST(LeaseSqlite, AnSqliteStoreHasNoLease) {
  testing::TempDb tmp;
  auto db = Store::open(tmp.path());
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto l = Lease::connect(db->location(), "x");
  ASSERT_FALSE(l.ok());
  EXPECT_EQ(l.error().code, ErrorCode::kUnsupported);
  auto state = read_lease(*db);
  ASSERT_TRUE(state.ok()) << state.error().message;
  EXPECT_EQ(state->epoch, 0);
  EXPECT_TRUE(fence_writes(*db, 3, "x").ok());
  EXPECT_TRUE(add_task(*db, row("t", 1), "added").ok());
}

}  // namespace
}  // namespace rondo::store
