// The schema migration runner (src/store/migrations.h): the real steps, and synthetic step lists
// that exercise what the real history does not have yet (data kept across steps, a failing step).
#include "migrations.h"

#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include "rondo/store/store.h"
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
  for (const char* table : {"tasks", "task_events", "traversals", "observations"}) {
    EXPECT_TRUE(db.tableExists(table)) << table;
  }
  EXPECT_EQ(db.execAndGet("SELECT \"table\" FROM pragma_foreign_key_list('task_events')").getString(), "tasks");
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
