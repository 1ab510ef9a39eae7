// Read-only commands never write (issue 14, point 4): `log stats` and `learn --db` open the store
// with OpenMode::kReadOnly; an empty or older file is refused with exit 2 and left byte-identical.
#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "app/cli_runner.h"
#include "migrations.h"
#include "rondo/core/traversal.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_log.h"
#include "store/temp_db.h"

namespace rondo::store {
namespace {

using rondo::test::run_cli;
using testing::TempDb;

std::string bytes_of(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// A store at the version before this build's: the schema steps but the last, as an older rondo
// left it. With a single step that is an empty database.
void make_older_store(const TempDb& tmp) {
  SQLite::Database raw(tmp.path(), SQLite::OPEN_READWRITE | SQLite::OPEN_CREATE);
  const auto steps = schema_migrations();
  ASSERT_TRUE(migrate(raw, steps.first(steps.size() - 1), tmp.path()).ok());
}

TEST(ReadOnly, CommandsRefuseAnEmptyOrOlderStoreAndLeaveItAsItWas) {
  struct Case {
    std::string name;
    std::function<void(const TempDb&)> make;
    std::string expect;
  };
  const Case cases[] = {
      {"empty file", [](const TempDb& t) { t.write(""); }, "an empty database, not yet a rondo store"},
      {"older schema", make_older_store,
       Store::latest_schema_version() > 1 ? "run 'rondo log migrate --db" : "an empty database"},
  };
  for (const auto& c : cases) {
    for (const std::string command : {"stats", "learn"}) {
      TempDb tmp;
      c.make(tmp);
      const std::string before = bytes_of(tmp.path());
      const auto models = tmp.str() + ".models.json";
      const auto r = command == "stats" ? run_cli({"log", "stats", "--db", tmp.str(), "--json"})
                                        : run_cli({"learn", "--db", tmp.str(), "-o", models});
      EXPECT_EQ(r.exit_code, 2) << c.name << ", " << command << ": " << r.err;
      EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.name << ", " << command << ": " << r.err;
      EXPECT_EQ(bytes_of(tmp.path()), before) << c.name << ", " << command;
      EXPECT_FALSE(std::filesystem::exists(models)) << c.name;
    }
  }
}

TEST(ReadOnly, AReadOnlyOpenWritesNothingToACurrentStore) {
  TempDb tmp;
  {
    auto db = Store::open(tmp.path());
    ASSERT_TRUE(db.ok());
    ASSERT_TRUE(
        add_traversal(*db, Traversal{"A_B", "A", "B", Time{} + seconds(1400000000), seconds(12), true, "t:1"}).ok());
  }
  {
    // Fold the WAL into the file, so that the file alone is the store.
    SQLite::Database raw(tmp.path(), SQLite::OPEN_READWRITE);
    raw.exec("PRAGMA wal_checkpoint(TRUNCATE)");
    raw.exec("PRAGMA journal_mode = DELETE");
  }
  const std::string before = bytes_of(tmp.path());
  const auto stats = run_cli({"log", "stats", "--db", tmp.str(), "--json"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_NE(stats.out.find("\"attempts\": 1"), std::string::npos) << stats.out;
  EXPECT_EQ(bytes_of(tmp.path()), before);  // not even switched to WAL
  SQLite::Database raw(tmp.path(), SQLite::OPEN_READONLY);
  EXPECT_EQ(raw.execAndGet("PRAGMA journal_mode").getString(), "delete");
}

TEST(ReadOnly, MigrateBringsAnOlderStoreUpToDate) {
  if (Store::latest_schema_version() < 2) GTEST_SKIP() << "only one schema version";
  TempDb tmp;
  make_older_store(tmp);
  const auto r = run_cli({"log", "migrate", "--db", tmp.str()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(run_cli({"log", "stats", "--db", tmp.str()}).exit_code, 0);
}

TEST(ReadOnly, LearnOnAnEdgeIdThatIsNotUtf8FailsAndKeepsTheModelsFile) {
  TempDb tmp;
  {
    auto db = Store::open(tmp.path());
    ASSERT_TRUE(db.ok());
    ASSERT_TRUE(
        add_traversal(*db, Traversal{"A\xff_B", "A\xff", "B", Time{} + seconds(1400000000), seconds(12), true, "t:1"})
            .ok());
  }
  const auto stats = run_cli({"log", "stats", "--db", tmp.str(), "--json"});
  EXPECT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_NE(stats.out.find("A\xef\xbf\xbd_B"), std::string::npos) << stats.out;  // U+FFFD for the bad byte
  const auto models = tmp.str() + ".models.json";
  { std::ofstream(models) << "{\"the\": \"old models\"}\n"; }
  const std::string before = bytes_of(models);
  const auto r = run_cli({"learn", "--db", tmp.str(), "-o", models});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(bytes_of(models), before);
  std::filesystem::remove(models);
}

TEST(ReadOnly, LogImportRefusesALogWhoseFileNameIsNotUtf8) {
  const auto dir = std::filesystem::temp_directory_path() / ("rondo-utf8-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "Aisle\xff_Ramp.data") << "1409644800 12.5 1\n";
  TempDb tmp;
  const auto r = run_cli({"log", "import", "--witham", dir.string(), "--db", tmp.str()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("Aisle?_Ramp.data: the file name is not valid UTF-8"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\xff'), std::string::npos);  // never echoed raw
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace rondo::store
