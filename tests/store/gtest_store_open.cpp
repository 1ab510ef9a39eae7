#include "rondo/store/store.h"

#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "rondo/store/task_table.h"
#include "rondo/store/traversal_log.h"
#include "rondo/store/traversal_stats.h"
#include "store/temp_db.h"

namespace rondo::store {
namespace {

using testing::TempDb;

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(StoreOpen, CreatesANewStoreInWalModeAtTheLatestVersion) {
  TempDb tmp;
  auto db = Store::open(tmp.path());
  ASSERT_TRUE(db.ok()) << db.error().message;
  EXPECT_EQ(db->file(), tmp.path());
  ASSERT_TRUE(db->schema_version().ok());
  EXPECT_EQ(*db->schema_version(), Store::latest_schema_version());

  SQLite::Database raw(tmp.path(), SQLite::OPEN_READONLY);
  EXPECT_EQ(raw.execAndGet("PRAGMA journal_mode").getString(), "wal");
  EXPECT_EQ(raw.execAndGet("PRAGMA user_version").getInt(), Store::latest_schema_version());
  EXPECT_EQ(raw.execAndGet("PRAGMA application_id").getInt(), 0x726f6e64);
  for (const char* table : {"tasks", "events", "traversals", "observations", "robot_state", "meta"}) {
    EXPECT_TRUE(raw.tableExists(table)) << table;
  }
}

TEST(StoreOpen, ReopensAndSharesAFileBetweenConnections) {
  TempDb tmp;
  auto first = Store::open(tmp.path());
  ASSERT_TRUE(first.ok()) << first.error().message;
  auto second = Store::open(tmp.path(), {.mode = OpenMode::kMustExist});
  ASSERT_TRUE(second.ok()) << second.error().message;
  Traversal t{"A_B", "A", "B", Time{seconds(100)}, seconds(5), true, ""};
  ASSERT_TRUE(add_traversal(*first, t).ok());
  EXPECT_EQ(*count_traversals(*second), 1u);
}

TEST(StoreOpen, MovedStoreKeepsWorking) {
  TempDb tmp;
  auto opened = Store::open(tmp.path());
  ASSERT_TRUE(opened.ok());
  Store moved = std::move(*opened);
  Store assigned = std::move(moved);
  EXPECT_TRUE(count_traversals(assigned).ok());
}

TEST(StoreOpen, MustExistRefusesAMissingFileAndDoesNotCreateIt) {
  TempDb tmp;
  auto db = Store::open(tmp.path(), {.mode = OpenMode::kMustExist});
  ASSERT_FALSE(db.ok());
  EXPECT_EQ(db.error().code, ErrorCode::kNotFound);
  EXPECT_NE(db.error().message.find(tmp.str()), std::string::npos) << db.error().message;
  EXPECT_FALSE(std::filesystem::exists(tmp.path()));
}

TEST(StoreOpen, RefusesAFolder) {
  TempDb tmp;
  std::filesystem::create_directory(tmp.path());
  for (OpenMode mode : {OpenMode::kCreateIfMissing, OpenMode::kMustExist}) {
    auto db = Store::open(tmp.path(), {.mode = mode});
    ASSERT_FALSE(db.ok());
    EXPECT_EQ(db.error().code, ErrorCode::kInvalidInput);
    EXPECT_NE(db.error().message.find("folder"), std::string::npos) << db.error().message;
  }
}

TEST(StoreOpen, MissingParentFolderIsAStorageErrorNotACrash) {
  TempDb tmp;
  auto db = Store::open(tmp.path() / "no" / "such" / "rondo.db");
  ASSERT_FALSE(db.ok());
  EXPECT_EQ(db.error().code, ErrorCode::kStorage);
  EXPECT_NE(db.error().message.find("rondo.db"), std::string::npos) << db.error().message;
}

TEST(StoreOpen, AnEmptyFileBecomesAnEmptyStore) {
  TempDb tmp;
  tmp.write("");
  auto db = Store::open(tmp.path(), {.mode = OpenMode::kMustExist});
  ASSERT_TRUE(db.ok()) << db.error().message;
  EXPECT_EQ(*count_traversals(*db), 0u);
}

TEST(StoreOpen, GarbageFilesAreRefusedUntouched) {
  std::string random_bytes(8192, '\0');
  std::mt19937 rng(7);
  for (char& c : random_bytes) c = static_cast<char>(rng() & 0xff);
  std::string bad_header = std::string("SQLite format 3") + '\0' + std::string(200, '\x7f');
  struct Case {
    const char* name;
    std::string bytes;
  };
  const Case cases[] = {
      {"text", "this is not a database\n"},
      {"json", R"({"tasks": []})"},
      {"random bytes", random_bytes},
      {"sqlite magic then garbage", bad_header},
      {"one byte", "x"},
  };
  for (const Case& c : cases) {
    TempDb tmp;
    tmp.write(c.bytes);
    for (OpenMode mode : {OpenMode::kCreateIfMissing, OpenMode::kMustExist}) {
      auto db = Store::open(tmp.path(), {.mode = mode});
      ASSERT_FALSE(db.ok()) << c.name;
      EXPECT_TRUE(db.error().code == ErrorCode::kInvalidInput || db.error().code == ErrorCode::kStorage) << c.name;
      EXPECT_NE(db.error().message.find(tmp.str()), std::string::npos) << c.name << ": " << db.error().message;
    }
    EXPECT_EQ(read_bytes(tmp.path()), c.bytes) << c.name << ": the file was changed";
  }
}

TEST(StoreOpen, NotADatabaseSaysSo) {
  TempDb tmp;
  tmp.write("this is not a database, it is a long enough line of text to fill a header ...........\n");
  auto db = Store::open(tmp.path());
  ASSERT_FALSE(db.ok());
  EXPECT_EQ(db.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(db.error().message.find("not an SQLite database"), std::string::npos) << db.error().message;
}

TEST(StoreOpen, ATruncatedStoreGivesAnErrorNotACrash) {
  TempDb tmp;
  {
    auto db = Store::open(tmp.path());
    ASSERT_TRUE(db.ok());
    std::vector<Traversal> many;
    for (int i = 0; i < 5000; ++i) {
      many.push_back({"E" + std::to_string(i % 7), "A", "B", Time{seconds(i)}, seconds(3), i % 2 == 0,
                      "test:" + std::to_string(i)});
    }
    ASSERT_TRUE(add_traversals(*db, many).ok());
  }  // closing checkpoints the WAL into the main file
  ASSERT_FALSE(std::filesystem::exists(tmp.wal()));
  const auto size = std::filesystem::file_size(tmp.path());
  std::filesystem::resize_file(tmp.path(), size / 2);

  auto db = Store::open(tmp.path(), {.mode = OpenMode::kMustExist});
  if (!db.ok()) {
    EXPECT_FALSE(db.error().message.empty());
    return;
  }
  auto summary = summarize_traversals(*db);
  ASSERT_FALSE(summary.ok()) << "half the pages are gone, yet the summary read";
  EXPECT_EQ(summary.error().code, ErrorCode::kStorage);
  EXPECT_NE(summary.error().message.find("corrupt"), std::string::npos) << summary.error().message;
}

TEST(StoreOpen, RefusesSqliteFilesThatAreNotRondoStores) {
  struct Case {
    const char* name;
    const char* sql;
  };
  const Case cases[] = {
      {"tables but no version", "CREATE TABLE tasks (x INTEGER)"},
      {"another application", "PRAGMA application_id = 1234"},
  };
  for (const Case& c : cases) {
    TempDb tmp;
    {
      SQLite::Database raw(tmp.path(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
      raw.exec(c.sql);
    }
    auto db = Store::open(tmp.path());
    ASSERT_FALSE(db.ok()) << c.name;
    EXPECT_EQ(db.error().code, ErrorCode::kInvalidInput) << c.name;
    EXPECT_NE(db.error().message.find("not a rondo database"), std::string::npos) << db.error().message;
    SQLite::Database raw(tmp.path(), SQLite::OPEN_READONLY);
    EXPECT_FALSE(raw.tableExists("traversals")) << c.name << ": the foreign file was migrated";
    EXPECT_EQ(raw.execAndGet("PRAGMA journal_mode").getString(), "delete")
        << c.name << ": the foreign file was changed";
  }
}

TEST(StoreOpen, RefusesANewerSchemaWithAClearMessage) {
  TempDb tmp;
  ASSERT_TRUE(Store::open(tmp.path()).ok());
  const int newer = Store::latest_schema_version() + 1;
  {
    SQLite::Database raw(tmp.path(), SQLite::OPEN_READWRITE);
    raw.exec("PRAGMA user_version = " + std::to_string(newer));
  }
  auto db = Store::open(tmp.path());
  ASSERT_FALSE(db.ok());
  EXPECT_EQ(db.error().code, ErrorCode::kUnsupported);
  EXPECT_NE(db.error().message.find("newer"), std::string::npos) << db.error().message;
  EXPECT_NE(db.error().message.find(std::to_string(newer)), std::string::npos) << db.error().message;
}

TEST(StoreOpen, ALockedStoreIsAStorageErrorAfterTheBusyTimeout) {
  TempDb tmp;
  ASSERT_TRUE(Store::open(tmp.path()).ok());
  auto db = Store::open(tmp.path(), {.busy_timeout = Duration{0}});
  ASSERT_TRUE(db.ok());
  SQLite::Database other(tmp.path(), SQLite::OPEN_READWRITE);
  other.exec("BEGIN IMMEDIATE");  // holds the write lock
  TaskRow task{"t1", Json::object(), "queued", Time{seconds(1)}, Time{seconds(1)}};
  Status added = add_task(*db, task);
  ASSERT_FALSE(added.ok());
  EXPECT_EQ(added.error().code, ErrorCode::kStorage);
  EXPECT_NE(added.error().message.find("locked"), std::string::npos) << added.error().message;
  other.exec("ROLLBACK");
  EXPECT_TRUE(add_task(*db, task).ok());
}

}  // namespace
}  // namespace rondo::store
