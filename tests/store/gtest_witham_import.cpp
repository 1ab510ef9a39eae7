#include "rondo/store/witham_import.h"

#include <gtest/gtest.h>

#include <fstream>

#include "rondo/core/traversal.h"
#include "rondo/store/traversal_stats.h"
#include "store/child_process.h"
#include "store/store_backends.h"

namespace rondo::store {
namespace {

using testing::kWithamAttempts;
using testing::kWithamSuccesses;
using testing::run_in_child;
using testing::TempDb;
using testing::witham_dir;

class WithamImport : public testing::BackendTest {
 protected:
  // A scratch path beside the test's files.
  std::filesystem::path scratch(const std::string& suffix) const { return scratch_.path().string() + suffix; }

 private:
  TempDb scratch_;
};

TEST_P(WithamImport, StoresEveryAttemptOfTheRealLogs) {
  Store db = open_store();
  auto report = import_witham_logs(db, witham_dir());
  ASSERT_TRUE(report.ok()) << report.error().message;
  EXPECT_EQ(report->attempts, kWithamAttempts);
  EXPECT_EQ(report->successes, kWithamSuccesses);
  EXPECT_EQ(report->edges, 62u);
  EXPECT_EQ(report->stored, (InsertCounts{kWithamAttempts, 0}));

  auto summary = summarize_traversals(db);
  ASSERT_TRUE(summary.ok());
  EXPECT_EQ(summary->attempts, static_cast<std::int64_t>(kWithamAttempts));
  EXPECT_EQ(summary->successes, static_cast<std::int64_t>(kWithamSuccesses));
  EXPECT_EQ(summary->edges.size(), 62u);

  // One edge, record for record, against the log file read directly.
  auto file = read_witham_edge_log(witham_dir() / "Aisle1_Aisle2.data");
  ASSERT_TRUE(file.ok());
  auto stored = find_traversals(db, {.edge_id = "Aisle1_Aisle2"});
  ASSERT_TRUE(stored.ok());
  auto expected = *file;
  std::stable_sort(expected.begin(), expected.end(), [](const auto& a, const auto& b) { return a.start < b.start; });
  EXPECT_EQ(*stored, expected);
}

TEST_P(WithamImport, ImportingTwiceAddsNothing) {
  Store db = open_store();
  ASSERT_TRUE(import_witham_logs(db, witham_dir()).ok());
  auto again = import_witham_logs(db, witham_dir());
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(again->stored, (InsertCounts{0, kWithamAttempts}));
  EXPECT_EQ(*count_traversals(db), kWithamAttempts);
}

TEST_P(WithamImport, CompletesAPartialLog) {
  Store db = open_store();
  auto all = read_witham_logs(witham_dir());
  ASSERT_TRUE(all.ok());
  ASSERT_TRUE(add_traversals(db, std::span(*all).subspan(1000, 500)).ok());
  auto report = import_witham_logs(db, witham_dir());
  ASSERT_TRUE(report.ok());
  EXPECT_EQ(report->stored, (InsertCounts{kWithamAttempts - 500, 500}));
  EXPECT_EQ(*count_traversals(db), kWithamAttempts);
}

// The import is one transaction: a process killed halfway leaves no rows, and the rerun stores
// every attempt exactly once.
TEST_P(WithamImport, AKilledImportLeavesNothingAndTheRerunCompletes) {
  constexpr std::size_t kKillAfter = 20000;
  auto end = run_in_child([&] {
    Store db = open_store();
    BatchOptions options{.progress =
                             [](std::size_t done, std::size_t) {
                               if (done >= kKillAfter) ::raise(SIGKILL);
                             },
                         .progress_every = 1000};
    (void)import_witham_logs(db, witham_dir(), options);
    ::_exit(5);  // not reached: the import was meant to die
  });
  ASSERT_TRUE(end.killed_by(SIGKILL)) << "child status " << end.status;
  // The dead writer left its WAL behind (SQLite spills big transactions to it before the commit);
  // frames without a commit record are ignored by the next reader.
  // A non-empty WAL shows the kill came after uncommitted rows had reached the disk. (PostgreSQL
  // rolls back the transaction of a connection that closes without a commit.)
  if (!postgres()) {
    ASSERT_TRUE(std::filesystem::exists(temp().file().wal()));
    const auto wal_bytes = std::filesystem::file_size(temp().file().wal());
    EXPECT_GT(wal_bytes, 0u);
    ::testing::Test::RecordProperty("wal_bytes_left_by_killed_import", std::to_string(wal_bytes));
  }

  Store db = open_store();
  EXPECT_EQ(*count_traversals(db), 0u) << "the killed import left partial rows";
  auto rerun = import_witham_logs(db, witham_dir());
  ASSERT_TRUE(rerun.ok()) << rerun.error().message;
  EXPECT_EQ(rerun->stored, (InsertCounts{kWithamAttempts, 0}));
  EXPECT_EQ(*count_traversals(db), kWithamAttempts);
  auto summary = summarize_traversals(db);
  ASSERT_TRUE(summary.ok());
  EXPECT_EQ(summary->successes, static_cast<std::int64_t>(kWithamSuccesses));
}

TEST_P(WithamImport, AMissingFolderIsNotFound) {
  Store db = open_store();
  auto report = import_witham_logs(db, scratch("-no-such-folder"));
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error().code, ErrorCode::kNotFound);
}

TEST_P(WithamImport, AMalformedLogStoresNothingAndNamesTheLine) {
  const std::filesystem::path dir = scratch("-logs");
  std::filesystem::create_directory(dir);
  std::ofstream(dir / "A_B.data") << "1404842483 67.6 0\n1404842551 10.3 1\n";
  std::ofstream(dir / "B_A.data") << "1404842483 67.6 0\n1404842551 ten 1\n";
  Store db = open_store();
  auto report = import_witham_logs(db, dir);
  std::filesystem::remove_all(dir);
  ASSERT_FALSE(report.ok());
  EXPECT_EQ(report.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(report.error().message.find("B_A.data:2"), std::string::npos) << report.error().message;
  EXPECT_EQ(*count_traversals(db), 0u);
}

RONDO_ON_BOTH_BACKENDS(WithamImport);

}  // namespace
}  // namespace rondo::store
