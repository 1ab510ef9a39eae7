// The schema migration runner (src/store/migrations.h): the real steps, and synthetic step lists
// that exercise what the real history does not have yet (data kept across steps, a failing step).
#include "migrations.h"

#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rondo/store/store.h"
#include "rondo/store/events.h"
#include "rondo/store/observations.h"
#include "rondo/store/task_table.h"
#include "rondo/store/traversal_log.h"
#include "store/temp_db.h"

namespace rondo::store {
namespace {

using testing::TempDb;

int user_version(SQLite::Database& db) {
  return db.execAndGet("PRAGMA user_version").getInt();
}

SQLite::Database raw_db(const TempDb& tmp) {
  return SQLite::Database(tmp.path(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
}

TEST(Migrations, RealStepsAreNumberedOneByOne) {
  const auto steps = schema_migrations();
  ASSERT_FALSE(steps.empty());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    EXPECT_EQ(steps[i].version, static_cast<int>(i) + 1);
    EXPECT_FALSE(steps[i].description.empty());
    EXPECT_FALSE(steps[i].sql.empty());
  }
  EXPECT_EQ(Store::latest_schema_version(), steps.back().version);
}

TEST(Migrations, FromEmptyToLatest) {
  TempDb tmp;
  auto db = raw_db(tmp);
  ASSERT_TRUE(migrate(db, schema_migrations(), tmp.path()).ok());
  EXPECT_EQ(user_version(db), Store::latest_schema_version());
  EXPECT_EQ(db.execAndGet("PRAGMA application_id").getInt(), kApplicationId);
  for (const char* table : {"tasks", "events", "traversals", "observations", "robot_state", "meta"}) {
    EXPECT_TRUE(db.tableExists(table)) << table;
  }
  EXPECT_FALSE(db.tableExists("task_events"));
  EXPECT_EQ(db.execAndGet("SELECT \"table\" FROM pragma_foreign_key_list('events')").getString(), "tasks");
}

// Version 1 -> 2: the task event log becomes the event log; every old event keeps its sequence
// number, time, task, name and reason, as a task event without a code, and new events follow it.
TEST(Migrations, Version1EventsBecomeTaskEventsOfTheEventLog) {
  TempDb tmp;
  {
    auto db = raw_db(tmp);
    ASSERT_TRUE(migrate(db, schema_migrations().first(1), tmp.path()).ok());
    db.exec("INSERT INTO tasks VALUES ('t1', 'failed', '{}', 10, 30), ('t2', 'queued', '{}', 20, 20)");
    db.exec("INSERT INTO task_events (time_ms, task_id, event, reason) VALUES (10, 't1', 'queued', 'added'), "
            "(20, 't2', 'queued', 'added'), (30, 't1', 'failed', 'too late: ...')");
  }
  auto store = Store::open(tmp.path());
  ASSERT_TRUE(store.ok()) << store.error().message;
  SQLite::Database db(tmp.path(), SQLite::OPEN_READONLY);
  SQLite::Statement q(db, "SELECT seq, time_ms, subject, task_id, event, code, reason FROM events ORDER BY seq");
  std::vector<std::string> rows;
  while (q.executeStep()) {
    rows.push_back(q.getColumn(0).getString() + " " + q.getColumn(1).getString() + " " + q.getColumn(2).getString() +
                   " " + q.getColumn(3).getString() + " " + q.getColumn(4).getString() + " [" +
                   q.getColumn(5).getString() + "] " + q.getColumn(6).getString());
  }
  EXPECT_EQ(rows, (std::vector<std::string>{"1 10 task t1 queued [] added", "2 20 task t2 queued [] added",
                                            "3 30 task t1 failed [] too late: ..."}));
  EXPECT_EQ(db.execAndGet("SELECT source || '|' || COALESCE(progress_json, 'null') FROM tasks WHERE id = 't1'")
                .getString(),
            "|null");
  // The sequence goes on after the migrated rows, and the log is still append-only.
  SQLite::Database rw(tmp.path(), SQLite::OPEN_READWRITE);
  rw.exec("INSERT INTO events (time_ms, subject, about, event) VALUES (40, 'robot', 'r', 'fault')");
  EXPECT_EQ(rw.execAndGet("SELECT MAX(seq) FROM events").getInt(), 4);
  EXPECT_THROW(rw.exec("DELETE FROM events"), SQLite::Exception);
  EXPECT_THROW(rw.exec("INSERT INTO events (time_ms, subject, event) VALUES (1, 'task', 'x')"), SQLite::Exception);
}

// Version 3 -> 4: tasks gain their planned start and end, none for the tasks already stored.
TEST(Migrations, Version3TasksGainNoPlannedTimes) {
  TempDb tmp;
  {
    auto db = raw_db(tmp);
    ASSERT_TRUE(migrate(db, schema_migrations().first(3), tmp.path()).ok());
    db.exec("INSERT INTO tasks (id, state, task_json, created_ms, updated_ms, source) "
            "VALUES ('t1', 'succeeded', '{\"id\": \"t1\"}', 10, 30, 'api')");
  }
  auto store = Store::open(tmp.path());
  ASSERT_TRUE(store.ok()) << store.error().message;
  auto old = get_task(*store, "t1");
  ASSERT_TRUE(old.ok()) << old.error().message;
  EXPECT_EQ(old->state, "succeeded");
  EXPECT_EQ(old->source, "api");
  EXPECT_FALSE(old->planned_start.has_value());
  EXPECT_FALSE(old->planned_end.has_value());
  // Written and read back from then on.
  ASSERT_TRUE(add_task(*store, TaskRow{.id = "t2",
                                       .task = Json{{"id", "t2"}},
                                       .state = "queued",
                                       .created = Time{seconds(40)},
                                       .updated = Time{seconds(40)}})
                  .ok());
  ASSERT_TRUE(set_task_state(*store, "t2", "failed", Time{seconds(50)}, "", "",
                             PlannedTimes{Time{seconds(42)}, Time{seconds(48)}})
                  .ok());
  auto now = get_task(*store, "t2");
  ASSERT_TRUE(now.ok()) << now.error().message;
  EXPECT_EQ(now->planned_start, Time{seconds(42)});
  EXPECT_EQ(now->planned_end, Time{seconds(48)});
}

// Version 4 -> 5 (a fleet): the rows of a single-robot store get its robot's name (robot_state's
// only row), except imported traversals and the events of requests and of the schedule; a task
// event appended later names its task's robot, a robot event its subject.
TEST(Migrations, Version4RowsGetTheirRobotsName) {
  TempDb tmp;
  {
    auto db = raw_db(tmp);
    ASSERT_TRUE(migrate(db, schema_migrations().first(4), tmp.path()).ok());
    db.exec("INSERT INTO tasks (id, state, task_json, created_ms, updated_ms) VALUES ('t1', 'queued', '{}', 10, 10)");
    db.exec("INSERT INTO events (time_ms, subject, task_id, event) VALUES (10, 'task', 't1', 'queued')");
    db.exec("INSERT INTO events (time_ms, subject, about, event) VALUES (11, 'robot', 'r1', 'departed'), "
            "(12, 'schedule', 'schedule', 'assumptions')");
    db.exec("INSERT INTO traversals (edge_id, from_node, to_node, start_ms, duration_ms, success, origin) VALUES "
            "('A_B', 'A', 'B', 10, 5, 1, NULL), ('A_B', 'A', 'B', 20, 5, 1, 'witham:A_B.data:1')");
    db.exec("INSERT INTO observations (what, place, time_ms, value) VALUES ('battery', 'A', 10, 0.5)");
    db.exec("INSERT INTO robot_state (robot, node, updated_ms) VALUES ('r1', 'A', 10)");
  }
  auto store = Store::open(tmp.path());
  ASSERT_TRUE(store.ok()) << store.error().message;
  EXPECT_EQ(get_task(*store, "t1")->robot, "r1");
  const std::vector<Event> events = read_events(*store).value();
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].robot, "r1");
  EXPECT_EQ(events[1].robot, "r1");
  EXPECT_EQ(events[2].robot, "");
  const std::vector<Traversal> log = find_traversals(*store).value();
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[0].robot, "r1");
  EXPECT_EQ(log[1].robot, "") << "an imported traversal's robot is not known";
  EXPECT_EQ(find_observations(*store).value().at(0).robot, "r1");
  EXPECT_EQ(find_traversals(*store, {.robot = "r1"}).value().size(), 1u);
  // From then on: a task event names its task's robot, a robot event its subject, unless told.
  ASSERT_TRUE(add_task(*store, TaskRow{.id = "t2", .task = Json{{"id", "t2"}}, .state = "queued",
                                       .created = Time{seconds(40)}, .updated = Time{seconds(40)}, .robot = "r2"}));
  ASSERT_TRUE(set_task_state(*store, "t2", "navigating", Time{seconds(41)}, "", ""));
  ASSERT_TRUE(append_event(*store, {.time = Time{seconds(42)}, .subject = Subject::kRobot, .about = "r3",
                                    .event = "fault"}));
  ASSERT_TRUE(set_task_robot(*store, "t2", "r4"));
  ASSERT_TRUE(set_task_state(*store, "t2", "queued", Time{seconds(43)}, "", ""));
  const std::vector<Event> later = read_events(*store, events.back().seq).value();
  ASSERT_EQ(later.size(), 4u);
  EXPECT_EQ(later[0].robot, "r2");
  EXPECT_EQ(later[1].robot, "r2");
  EXPECT_EQ(later[2].robot, "r3");
  EXPECT_EQ(later[3].robot, "r4");
  EXPECT_EQ(get_task(*store, "t2")->robot, "r4");
  EXPECT_FALSE(set_task_robot(*store, "nope", "r1"));
}

// Version 6 -> 7 (events about the executive): SQLite makes the events table again; every row keeps
// its sequence number and fields, numbering continues after the highest ever given (AUTOINCREMENT's
// mark, above the last row left), the log is still append-only, and an executive event is taken.
TEST(Migrations, Version6EventsAreKeptAndTheExecutiveIsASubject) {
  TempDb tmp;
  {
    auto db = raw_db(tmp);
    ASSERT_TRUE(migrate(db, schema_migrations().first(6), tmp.path()).ok());
    db.exec("INSERT INTO tasks (id, state, task_json, created_ms, updated_ms) VALUES ('t1', 'queued', '{}', 10, 10)");
    db.exec(
        "INSERT INTO events (seq, time_ms, subject, task_id, event, robot, epoch) VALUES "
        "(3, 10, 'task', 't1', 'queued', 'r1', 0), (8, 12, 'schedule', NULL, 'assumptions', '', 0), "
        "(9, 13, 'robot', NULL, 'fault', 'r1', 0)");
    db.exec("DROP TRIGGER events_no_delete; DELETE FROM events WHERE seq = 9");  // as retention does
    EXPECT_THROW(db.exec("INSERT INTO events (time_ms, subject, event) VALUES (1, 'executive', 'takeover')"),
                 SQLite::Exception);
  }
  auto store = Store::open(tmp.path());
  ASSERT_TRUE(store.ok()) << store.error().message;
  const std::vector<Event> events = read_events(*store).value();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].seq, 3);
  EXPECT_EQ(events[0].task_id, "t1");
  EXPECT_EQ(events[0].robot, "r1");
  EXPECT_EQ(events[1].seq, 8);
  EXPECT_EQ(events[1].subject, Subject::kSchedule);
  const auto taken = append_event(
      *store,
      {.time = Time{seconds(20)}, .subject = Subject::kExecutive, .about = "rondo-serve-1", .event = "takeover"});
  ASSERT_TRUE(taken.ok()) << taken.error().message;
  EXPECT_EQ(*taken, 10) << "a sequence number once given is never given again";
  auto db = raw_db(tmp);
  EXPECT_THROW(db.exec("UPDATE events SET reason = 'x'"), SQLite::Exception);
  EXPECT_THROW(db.exec("DELETE FROM events"), SQLite::Exception);
  EXPECT_EQ(db.execAndGet("SELECT COUNT(*) FROM sqlite_schema WHERE name IN ('events_by_task', 'events_no_update', "
                          "'events_no_delete')")
                .getInt(),
            3);
}

// Every older version of the real schema opens and ends at the latest one.
TEST(Migrations, FromEachOlderVersionToLatest) {
  const auto steps = schema_migrations();
  for (std::size_t old = 0; old < steps.size(); ++old) {
    TempDb tmp;
    {
      auto db = raw_db(tmp);
      ASSERT_TRUE(migrate(db, steps.first(old), tmp.path()).ok()) << "building version " << old;
      EXPECT_EQ(user_version(db), static_cast<int>(old));
    }
    auto store = Store::open(tmp.path());
    ASSERT_TRUE(store.ok()) << "from version " << old << ": " << store.error().message;
    EXPECT_EQ(*store->schema_version(), Store::latest_schema_version()) << "from version " << old;
  }
}

TEST(Migrations, RunningAgainChangesNothing) {
  TempDb tmp;
  auto db = raw_db(tmp);
  ASSERT_TRUE(migrate(db, schema_migrations(), tmp.path()).ok());
  const int changes = db.getTotalChanges();
  ASSERT_TRUE(migrate(db, schema_migrations(), tmp.path()).ok());
  EXPECT_EQ(db.getTotalChanges(), changes);
  EXPECT_EQ(user_version(db), Store::latest_schema_version());
}

constexpr Migration kSynthetic[] = {
    {1, "a table", "CREATE TABLE things (name TEXT NOT NULL)"},
    {2, "a column with a default", "ALTER TABLE things ADD COLUMN size INTEGER NOT NULL DEFAULT 7"},
    {3, "an index and a backfill", "CREATE INDEX things_by_name ON things (name); UPDATE things SET size = 8"},
};

TEST(Migrations, DataSurvivesEachLaterStep) {
  for (std::size_t start = 1; start < std::size(kSynthetic); ++start) {
    TempDb tmp;
    auto db = raw_db(tmp);
    ASSERT_TRUE(migrate(db, std::span(kSynthetic).first(start), tmp.path()).ok());
    db.exec("INSERT INTO things (name) VALUES ('kept')");
    ASSERT_TRUE(migrate(db, kSynthetic, tmp.path()).ok()) << "from version " << start;
    EXPECT_EQ(user_version(db), 3);
    EXPECT_EQ(db.execAndGet("SELECT name FROM things").getString(), "kept");
    EXPECT_EQ(db.execAndGet("SELECT size FROM things").getInt(), 8);
  }
}

TEST(Migrations, AFailingStepIsRolledBackWhole) {
  const Migration broken[] = {
      kSynthetic[0],
      {2, "half good", "CREATE TABLE extra (x INTEGER); INSERT INTO no_such_table VALUES (1)"},
  };
  TempDb tmp;
  auto db = raw_db(tmp);
  Status s = migrate(db, broken, tmp.path());
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::kStorage);
  EXPECT_NE(s.error().message.find("schema step 2"), std::string::npos) << s.error().message;
  EXPECT_EQ(user_version(db), 1);  // step 1 stays committed
  EXPECT_TRUE(db.tableExists("things"));
  EXPECT_FALSE(db.tableExists("extra"));  // step 2 left nothing behind
}

TEST(Migrations, RefusesANewerVersionWithoutTouchingIt) {
  TempDb tmp;
  auto db = raw_db(tmp);
  ASSERT_TRUE(migrate(db, kSynthetic, tmp.path()).ok());
  Status s = migrate(db, std::span(kSynthetic).first(2), tmp.path());
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::kUnsupported);
  EXPECT_NE(s.error().message.find("schema version 3 is newer than this rondo knows (2)"), std::string::npos)
      << s.error().message;
  EXPECT_EQ(user_version(db), 3);
}

}  // namespace
}  // namespace rondo::store
