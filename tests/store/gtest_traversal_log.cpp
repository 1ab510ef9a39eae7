#include "rondo/store/traversal_log.h"

#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include "rondo/store/traversal_stats.h"
#include "db/pg_connection.h"
#include "store/store_backends.h"

namespace rondo::store {
namespace {


Time at(int s) {
  return Time{seconds(s)};
}

Traversal crossing(std::string edge, int start_s, int duration_ms, bool ok, std::string origin = "") {
  const auto sep = edge.find('_');
  return Traversal{edge, edge.substr(0, sep), edge.substr(sep + 1), at(start_s), Duration{duration_ms},
                   ok,   std::move(origin)};
}

class TraversalLog : public testing::BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (HasFatalFailure()) return;
    auto opened = temp().open();
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    db_.emplace(std::move(*opened));
  }
  Store& db() { return *db_; }
  std::size_t count() { return *count_traversals(db()); }

  std::optional<Store> db_;
};

TEST_P(TraversalLog, RoundTripsEveryFieldWithAndWithoutOrigin) {
  Traversal live = crossing("A_B", 1000, 12345, true);
  live.robot = "r2";
  live.waited = milliseconds(41250);  // waited for another robot before it set out
  const Traversal imported = crossing("B_A", 999, 7, false, "witham:B_A.data:3");
  ASSERT_TRUE(*add_traversal(db(), live));
  ASSERT_TRUE(*add_traversal(db(), imported));
  auto all = find_traversals(db());
  ASSERT_TRUE(all.ok()) << all.error().message;
  EXPECT_EQ(*all, (std::vector<Traversal>{imported, live}));  // by start time

  // A live traversal has no origin: NULL in the table, not an empty string.
  EXPECT_EQ(temp().raw_sql("DELETE FROM traversals WHERE origin IS NULL AND edge_id = 'A_B'"), "");
  EXPECT_EQ(*find_traversals(db()), (std::vector<Traversal>{imported}));
}

TEST_P(TraversalLog, StoresAnOriginOnceAndLiveTraversalsAlways) {
  const Traversal live = crossing("A_B", 10, 500, true);
  EXPECT_TRUE(*add_traversal(db(), live));
  EXPECT_TRUE(*add_traversal(db(), live));
  const Traversal imported = crossing("A_B", 10, 500, true, "log:1");
  EXPECT_TRUE(*add_traversal(db(), imported));
  EXPECT_FALSE(*add_traversal(db(), imported));
  EXPECT_EQ(count(), 3u);
}

TEST_P(TraversalLog, BatchCountsInsertedAndAlreadyPresent) {
  std::vector<Traversal> first{crossing("A_B", 1, 1, true, "o1"), crossing("A_B", 2, 1, true, "o2")};
  auto n = add_traversals(db(), first);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, (InsertCounts{2, 0}));

  std::vector<Traversal> second{crossing("A_B", 2, 1, true, "o2"), crossing("A_B", 3, 1, true, "o3"),
                                crossing("A_B", 4, 1, true)};
  n = add_traversals(db(), second);
  ASSERT_TRUE(n.ok());
  EXPECT_EQ(*n, (InsertCounts{2, 1}));
  EXPECT_EQ(count(), 4u);
}

TEST_P(TraversalLog, ABatchThatFailsStoresNothing) {
  std::vector<Traversal> batch{crossing("A_B", 1, 1, true, "o1"), crossing("A_B", 2, 1, true, "o2"),
                               crossing("A_B", 3, -5, true, "o3")};  // a negative duration breaks a CHECK
  auto n = add_traversals(db(), batch);
  ASSERT_FALSE(n.ok());
  EXPECT_EQ(n.error().code, ErrorCode::kStorage);
  EXPECT_EQ(count(), 0u);
  batch.pop_back();
  EXPECT_EQ(*add_traversals(db(), batch), (InsertCounts{2, 0}));
}

TEST_P(TraversalLog, ReportsProgressEveryNRows) {
  std::vector<Traversal> batch;
  for (int i = 0; i < 10; ++i) batch.push_back(crossing("A_B", i, 1, true));
  std::vector<std::pair<std::size_t, std::size_t>> calls;
  BatchOptions options{.progress = [&](std::size_t done, std::size_t total) { calls.emplace_back(done, total); },
                       .progress_every = 4};
  ASSERT_TRUE(add_traversals(db(), batch, options).ok());
  EXPECT_EQ(calls, (std::vector<std::pair<std::size_t, std::size_t>>{{4, 10}, {8, 10}}));
}

TEST_P(TraversalLog, QueriesByEdgeAndTimeRange) {
  ASSERT_TRUE(add_traversals(db(),
                             std::vector<Traversal>{
                                 crossing("A_B", 10, 1, true, "1"),
                                 crossing("B_C", 20, 1, true, "2"),
                                 crossing("A_B", 30, 1, false, "3"),
                                 crossing("A_B", 40, 1, true, "4"),
                                 crossing("B_C", 30, 1, true, "5"),
                             })
                  .ok());
  struct Case {
    const char* name;
    TraversalQuery query;
    std::vector<std::string> origins;
  };
  const Case cases[] = {
      {"all, by start then edge", {}, {"1", "2", "3", "5", "4"}},
      {"one edge", {.edge_id = "A_B"}, {"1", "3", "4"}},
      {"unknown edge", {.edge_id = "X_Y"}, {}},
      {"from (inclusive)", {.from = at(30)}, {"3", "5", "4"}},
      {"until (exclusive)", {.until = at(30)}, {"1", "2"}},
      {"range", {.from = at(20), .until = at(40)}, {"2", "3", "5"}},
      {"edge and range", {.edge_id = "A_B", .from = at(20), .until = at(41)}, {"3", "4"}},
      {"empty range", {.from = at(40), .until = at(40)}, {}},
  };
  for (const Case& c : cases) {
    auto found = find_traversals(db(), c.query);
    ASSERT_TRUE(found.ok()) << c.name << ": " << found.error().message;
    std::vector<std::string> origins;
    for (const auto& t : *found) origins.push_back(t.origin);
    EXPECT_EQ(origins, c.origins) << c.name;
  }
}

TEST_P(TraversalLog, TheLearnersQueryUsesTheEdgeStartIndex) {
  if (postgres()) {
    // An empty table is scanned whole by choice; with scans priced out the planner shows what index
    // it has for the query.
    auto raw = db::PgConnection::connect({.conninfo = temp().url(), .password = std::nullopt});
    raw->exec_script("SET enable_seqscan = off");
    auto plan = raw->query(
        "EXPLAIN SELECT * FROM traversals WHERE edge_id = 'A_B' AND start_ms >= 0 AND start_ms < 10 ORDER BY start_ms");
    std::string details;
    while (plan->next()) details += plan->text(0) + "\n";
    EXPECT_NE(details.find("traversals_by_edge_start"), std::string::npos) << details;
    return;
  }
  SQLite::Database raw(temp().file().path(), SQLite::OPEN_READONLY);
  SQLite::Statement plan(raw,
                         "EXPLAIN QUERY PLAN SELECT * FROM traversals WHERE edge_id = 'A_B' AND start_ms >= 0 "
                         "AND start_ms < 10 ORDER BY start_ms");
  std::string details;
  while (plan.executeStep()) details += plan.getColumn(3).getString() + "\n";
  EXPECT_NE(details.find("traversals_by_edge_start"), std::string::npos) << details;
}

TEST_P(TraversalLog, SummarisesPerEdge) {
  ASSERT_TRUE(add_traversals(db(),
                             std::vector<Traversal>{
                                 crossing("A_B", 30, 1000, true),
                                 crossing("A_B", 10, 3000, true),
                                 crossing("A_B", 20, 90000, false),  // failures do not count in the mean
                                 crossing("B_C", 5, 4000, false),
                             })
                  .ok());
  auto s = summarize_traversals(db());
  ASSERT_TRUE(s.ok()) << s.error().message;
  EXPECT_EQ(s->attempts, 4);
  EXPECT_EQ(s->successes, 2);
  ASSERT_EQ(s->edges.size(), 2u);
  const EdgeSummary& ab = s->edges[0];
  EXPECT_EQ(ab.edge_id, "A_B");
  EXPECT_EQ(ab.from, "A");
  EXPECT_EQ(ab.to, "B");
  EXPECT_EQ(ab.attempts, 3);
  EXPECT_EQ(ab.successes, 2);
  EXPECT_EQ(ab.first_start, at(10));
  EXPECT_EQ(ab.last_start, at(30));
  EXPECT_EQ(ab.mean_success_duration, std::optional<Duration>(Duration{2000}));
  EXPECT_EQ(s->edges[1].edge_id, "B_C");
  EXPECT_EQ(s->edges[1].mean_success_duration, std::nullopt);
}

TEST_P(TraversalLog, AnEmptyLogSummarisesToZero) {
  auto s = summarize_traversals(db());
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->attempts, 0);
  EXPECT_EQ(s->successes, 0);
  EXPECT_TRUE(s->edges.empty());
}

RONDO_ON_BOTH_BACKENDS(TraversalLog);

}  // namespace
}  // namespace rondo::store
