// store::backup_store and store::archive_old_records (backup.h), and their commands
// `rondo backup` and `rondo log archive`.
#include "rondo/store/backup.h"

#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "app/cli_runner.h"
#include "migrations.h"
#include "rondo/store/events.h"
#include "rondo/store/task_table.h"
#include "rondo/store/traversal_log.h"
#include "store/temp_db.h"

namespace rondo::store {
namespace {

using testing::TempDb;

Time day(int d, int hour = 12) {
  return Time{hours(24 * d + hour)};
}

TaskRow row(const std::string& id, Time t) {
  return {.id = id, .task = Json{{"id", id}}, .state = "queued", .created = t, .updated = t, .source = "test"};
}

std::int64_t count(const std::filesystem::path& file, const std::string& table) {
  SQLite::Database db(file.string(), SQLite::OPEN_READONLY);
  return db.execAndGet("SELECT COUNT(*) FROM " + table).getInt64();
}

TEST(Backup, CopiesEveryCommittedRowIntoACheckedFileAndNeverOverwrites) {
  TempDb live, copy;
  auto db = Store::open(live.path()).value();
  for (int i = 0; i < 50; ++i) ASSERT_TRUE(add_task(db, row("t" + std::to_string(i), day(1))));
  const BackupReport report = backup_store(db, copy.path()).value();
  EXPECT_EQ(report.file, copy.path());
  EXPECT_GT(report.pages, 0);
  EXPECT_EQ(report.bytes, std::filesystem::file_size(copy.path()));
  EXPECT_FALSE(std::filesystem::exists(copy.str() + ".part"));
  EXPECT_EQ(count(copy.path(), "tasks"), 50);
  EXPECT_EQ(count(copy.path(), "events"), 50);
  // The copy is a store of the current schema: it opens read-only, as `rondo log stats` would.
  EXPECT_TRUE(Store::open(copy.path(), {.mode = OpenMode::kReadOnly}).ok());

  const auto again = backup_store(db, copy.path());
  ASSERT_FALSE(again.ok());
  EXPECT_EQ(again.error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(count(copy.path(), "tasks"), 50);  // untouched
}

TEST(Backup, IsOneConsistentSnapshotWhileAnotherConnectionWrites) {
  TempDb live, copy;
  auto db = Store::open(live.path()).value();
  for (int i = 0; i < 200; ++i) ASSERT_TRUE(add_task(db, row("before" + std::to_string(i), day(1))));
  std::atomic<bool> done{false};
  std::atomic<int> written{0};
  std::thread writer([&] {  // `rondo serve` committing tasks meanwhile, on its own connection
    auto w = Store::open(live.path(), {.sync_commits = false}).value();
    while (!done || written < 20)
      if (add_task(w, row("during" + std::to_string(written), day(2)))) ++written;
  });
  auto reader = Store::open(live.path(), {.mode = OpenMode::kMustExist}).value();
  const auto report = backup_store(reader, copy.path());
  done = true;
  writer.join();
  ASSERT_TRUE(report.ok()) << report.error().message;
  // Every task has exactly its one "added" event in the copy: no half-written transaction.
  SQLite::Database c(copy.str(), SQLite::OPEN_READONLY);
  const std::int64_t tasks = c.execAndGet("SELECT COUNT(*) FROM tasks").getInt64();
  EXPECT_GE(tasks, 200);
  EXPECT_LE(tasks, 200 + written.load());
  EXPECT_EQ(c.execAndGet("SELECT COUNT(*) FROM events").getInt64(), tasks);
  EXPECT_EQ(c.execAndGet("PRAGMA integrity_check").getString(), "ok");
}

// A store of 30 days: tasks that ended early, one that never finished, traversals every day.
struct ThirtyDays {
  TempDb live, archive;
  Store db = Store::open(live.path()).value();
  ThirtyDays() {
    for (int d = 0; d < 30; ++d) {
      const std::string id = "day" + std::to_string(d);
      EXPECT_TRUE(add_task(db, row(id, day(d, 8))));
      EXPECT_TRUE(set_task_state(db, id, "succeeded", day(d, 9), "done", "done"));
      EXPECT_TRUE(add_traversal(db, {.edge_id = "e", .from = "a", .to = "b", .start = day(d, 10),
                                     .duration = seconds(30), .success = true}));
      EXPECT_TRUE(append_event(db, {.time = day(d, 11), .subject = Subject::kRobot, .about = "robot",
                                    .event = "battery", .code = "battery"}));
    }
    EXPECT_TRUE(add_task(db, row("waiting", day(0, 7))));  // old, but not finished
  }
};

// An archive made by an older build (schema 3: tasks without their planned times) is added to:
// it gains the columns added since, NULL in its rows.
TEST(Archive, AddsToAnArchiveOfAnOlderSchema) {
  ThirtyDays s;
  {
    SQLite::Database old(s.archive.path(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
    ASSERT_TRUE(migrate(old, schema_migrations().first(3), s.archive.path()).ok());
  }
  // Its events table knows no executive subject (version 7): it is made again, and takes one.
  ASSERT_TRUE(append_event(
      s.db, {.time = day(1, 13), .subject = Subject::kExecutive, .about = "rondo-serve-1", .event = "takeover"}));
  const auto r = archive_old_records(s.db, hours(24 * 20), hours(24 * 14), s.archive.path());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_GT(r->tasks, 0);
  {
    SQLite::Database archived(s.archive.path(), SQLite::OPEN_READONLY);
    EXPECT_EQ(archived.execAndGet("SELECT COUNT(*) FROM events WHERE subject = 'executive'").getInt(), 1);
  }
  EXPECT_EQ(count(s.archive.path(), "tasks"), r->tasks);
  SQLite::Database archived(s.archive.path(), SQLite::OPEN_READONLY);
  EXPECT_EQ(archived.execAndGet("SELECT COUNT(*) FROM tasks WHERE planned_start_ms IS NULL AND planned_end_ms IS NULL")
                .getInt64(),
            r->tasks);
}

TEST(Archive, MovesOldFinishedTasksEventsAndTraversalsAndKeepsTheRest) {
  ThirtyDays s;
  const std::int64_t tasks0 = count(s.live.path(), "tasks"), events0 = count(s.live.path(), "events"),
                     trav0 = count(s.live.path(), "traversals");
  // The latest record is day 29 at 11:00; 20 days back is day 9 at 11:00.
  const ArchiveReport r = archive_old_records(s.db, hours(24 * 20), hours(24 * 14), s.archive.path()).value();
  ASSERT_TRUE(r.cut);
  EXPECT_EQ(*r.latest, day(29, 11));
  EXPECT_EQ(*r.cut, day(9, 11));
  EXPECT_EQ(r.tasks, 10);          // days 0..9: they ended at 09:00, before the cut
  EXPECT_EQ(r.traversals, 10);     // days 0..9: they started at 10:00
  EXPECT_EQ(r.events, 10 * 2 + 9);  // those tasks' two events each; the robot's of days 0..8 (day 9's is at the cut)
  // Every row is in exactly one of the two files.
  EXPECT_EQ(count(s.live.path(), "tasks") + count(s.archive.path(), "tasks"), tasks0);
  EXPECT_EQ(count(s.live.path(), "events") + count(s.archive.path(), "events"), events0);
  EXPECT_EQ(count(s.live.path(), "traversals") + count(s.archive.path(), "traversals"), trav0);
  EXPECT_EQ(count(s.archive.path(), "tasks"), r.tasks);
  // The unfinished task and its events stay, however old.
  EXPECT_TRUE(get_task(s.db, "waiting").ok());
  EXPECT_FALSE(read_events_of(s.db, "waiting").value().empty());
  // The learning window (14 days back from the latest record) is whole in the live store.
  const TraversalQuery window{.from = day(29, 11) - hours(24 * 14)};
  EXPECT_EQ(find_traversals(s.db, window).value().size(), 14u);
  // The event log is append-only again.
  EXPECT_THROW(SQLite::Database(s.live.str(), SQLite::OPEN_READWRITE).exec("DELETE FROM events"), SQLite::Exception);
}

TEST(Archive, RunningItAgainMovesNothingAndCopiesNothingTwice) {
  ThirtyDays s;
  ASSERT_TRUE(archive_old_records(s.db, hours(24 * 20), hours(24 * 14), s.archive.path()).ok());
  const std::int64_t archived = count(s.archive.path(), "events");
  const ArchiveReport again = archive_old_records(s.db, hours(24 * 20), hours(24 * 14), s.archive.path()).value();
  EXPECT_EQ(again.tasks + again.events + again.traversals, 0);
  EXPECT_EQ(count(s.archive.path(), "events"), archived);
}

TEST(Archive, RefusesAnAgeInsideTheLearningWindowAndDoesNothingToAnEmptyStore) {
  ThirtyDays s;
  const auto refused = archive_old_records(s.db, hours(24 * 7), hours(24 * 14), s.archive.path());
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(refused.error().message.find("learning window"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(s.archive.path()));

  TempDb empty, archive;
  auto db = Store::open(empty.path()).value();
  const ArchiveReport r = archive_old_records(db, hours(24 * 30), hours(24 * 14), archive.path()).value();
  EXPECT_FALSE(r.cut);
}

TEST(BackupCommands, BackupAndArchiveFromTheCommandLine) {
  ThirtyDays s;
  TempDb copy;
  const std::filesystem::path dir = s.live.path().parent_path();
  auto ok = rondo::test::run_cli({"backup", "--db", s.live.str(), copy.str()});
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("integrity ok"), std::string::npos);
  EXPECT_EQ(rondo::test::run_cli({"backup", "--db", s.live.str(), copy.str()}).exit_code, 2);  // exists
  EXPECT_EQ(rondo::test::run_cli({"backup", copy.str()}).exit_code, 2);  // no source
  EXPECT_EQ(rondo::test::run_cli({"backup", "--data", (dir / "no-such-folder").string(), copy.str() + "x"}).exit_code, 2);

  EXPECT_EQ(rondo::test::run_cli({"log", "archive", "--db", s.live.str(), "--older-than", "7d", "--out",
                                  s.archive.str()}).exit_code, 2);
  EXPECT_EQ(rondo::test::run_cli({"log", "archive", "--db", s.live.str(), "--older-than", "soon", "--out",
                                  s.archive.str()}).exit_code, 2);
  auto moved = rondo::test::run_cli({"log", "archive", "--db", s.live.str(), "--older-than", "20d", "--out",
                                     s.archive.str()});
  EXPECT_EQ(moved.exit_code, 0) << moved.err;
  EXPECT_NE(moved.out.find("10 finished tasks"), std::string::npos) << moved.out;
}

}  // namespace
}  // namespace rondo::store
