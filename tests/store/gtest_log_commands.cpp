// `rondo log import` and `rondo log stats`, run in-process through rondo::app::run.
#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include "app/cli_runner.h"
#include "rondo/core/document.h"
#include "rondo/store/store.h"
#include "store/temp_db.h"

namespace rondo::store {
namespace {

using testing::kWithamAttempts;
using testing::kWithamSuccesses;
using testing::TempDb;
using testing::witham_dir;

using CliRun = rondo::test::CliResult;
using rondo::test::run_cli;

TEST(LogCommands, ImportThenStatsJsonCountsEveryAttempt) {
  TempDb tmp;
  CliRun imported = run_cli({"log", "import", "--witham", witham_dir().string(), "--db", tmp.str()});
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  EXPECT_NE(imported.out.find("attempts:        32078"), std::string::npos) << imported.out;
  EXPECT_NE(imported.out.find("successes:       21916"), std::string::npos) << imported.out;
  EXPECT_NE(imported.out.find("inserted:        32078"), std::string::npos) << imported.out;
  EXPECT_NE(imported.out.find("already present: 0"), std::string::npos) << imported.out;

  CliRun stats = run_cli({"log", "stats", "--db", tmp.str(), "--json"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  const Json j = Json::parse(stats.out);
  EXPECT_EQ(j["attempts"], kWithamAttempts);
  EXPECT_EQ(j["successes"], kWithamSuccesses);
  EXPECT_EQ(j["edges"], 62);
  ASSERT_EQ(j["per_edge"].size(), 62u);
  std::size_t attempts = 0;
  for (const auto& e : j["per_edge"]) attempts += e["attempts"].get<std::size_t>();
  EXPECT_EQ(attempts, kWithamAttempts);
  const Json& first = j["per_edge"][0];
  EXPECT_EQ(first["edge"], "Aisle1_Aisle2");
  EXPECT_EQ(first["from"], "Aisle1");
  EXPECT_EQ(first["to"], "Aisle2");
  EXPECT_TRUE(first["first"].is_string());
  EXPECT_TRUE(first["mean_success_duration_s"].is_number());
}

TEST(LogCommands, ImportTwiceReportsWhatWasAlreadyThere) {
  TempDb tmp;
  ASSERT_EQ(run_cli({"log", "import", "--witham", witham_dir().string(), "--db", tmp.str()}).exit_code, 0);
  CliRun again = run_cli({"log", "import", "--witham", witham_dir().string(), "--db", tmp.str(), "--json"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const Json j = Json::parse(again.out);
  EXPECT_EQ(j["attempts"], kWithamAttempts);
  EXPECT_EQ(j["inserted"], 0);
  EXPECT_EQ(j["already_present"], kWithamAttempts);
}

TEST(LogCommands, StatsTableHasARowPerEdgeAndATotal) {
  TempDb tmp;
  ASSERT_EQ(run_cli({"log", "import", "--witham", witham_dir().string(), "--db", tmp.str()}).exit_code, 0);
  CliRun stats = run_cli({"log", "stats", "--db", tmp.str()});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  EXPECT_NE(stats.out.find("Aisle1_Aisle2"), std::string::npos);
  EXPECT_NE(stats.out.find("total (62 edges)"), std::string::npos) << stats.out;
  EXPECT_NE(stats.out.find("32078"), std::string::npos);
  EXPECT_EQ(std::count(stats.out.begin(), stats.out.end(), '\n'), 64);  // header + 62 + total
}

TEST(LogCommands, StatsOfAnEmptyStoreIsZero) {
  TempDb tmp;
  ASSERT_TRUE(Store::open(tmp.path()).ok());
  CliRun stats = run_cli({"log", "stats", "--db", tmp.str(), "--json"});
  ASSERT_EQ(stats.exit_code, 0) << stats.err;
  const Json j = Json::parse(stats.out);
  EXPECT_EQ(j["attempts"], 0);
  EXPECT_EQ(j["successes"], 0);
  EXPECT_TRUE(j["per_edge"].empty());
}

TEST(LogCommands, StatsOfAMissingFileIsBadInputAndCreatesNothing) {
  TempDb tmp;
  CliRun stats = run_cli({"log", "stats", "--db", tmp.str(), "--json"});
  EXPECT_EQ(stats.exit_code, 2);
  EXPECT_TRUE(stats.out.empty());
  EXPECT_NE(stats.err.find(tmp.str() + ": no such database file"), std::string::npos) << stats.err;
  EXPECT_FALSE(std::filesystem::exists(tmp.path()));
}

TEST(LogCommands, StatsOfAFileThatIsNotADatabaseIsBadInput) {
  TempDb tmp;
  tmp.write("edge,attempts\nA_B,3\nthis is a csv file, not a database, and it is long enough.........\n");
  CliRun stats = run_cli({"log", "stats", "--db", tmp.str()});
  EXPECT_EQ(stats.exit_code, 2);
  EXPECT_NE(stats.err.find("not an SQLite database"), std::string::npos) << stats.err;
  EXPECT_NE(stats.err.find(tmp.str()), std::string::npos) << stats.err;
}

TEST(LogCommands, StatsOfANewerStoreFailsClearly) {
  TempDb tmp;
  ASSERT_TRUE(Store::open(tmp.path()).ok());
  {
    SQLite::Database raw(tmp.path(), SQLite::OPEN_READWRITE);
    raw.exec("PRAGMA user_version = 999");
  }
  CliRun stats = run_cli({"log", "stats", "--db", tmp.str()});
  EXPECT_EQ(stats.exit_code, 1);
  EXPECT_NE(stats.err.find("schema version 999 is newer"), std::string::npos) << stats.err;
}

TEST(LogCommands, BadArgumentsAreBadInput) {
  TempDb tmp;
  struct Case {
    const char* name;
    std::vector<std::string> args;
  };
  const Case cases[] = {
      {"no subcommand", {"log"}},
      {"import without --witham", {"log", "import", "--db", tmp.str()}},
      {"import without --db", {"log", "import", "--witham", witham_dir().string()}},
      {"import of a missing folder", {"log", "import", "--witham", tmp.str() + "-missing", "--db", tmp.str()}},
      {"stats without --db", {"log", "stats"}},
  };
  for (const Case& c : cases) {
    CliRun r = run_cli(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.name << ": " << r.err;
    EXPECT_NE(r.err.find("rondo: error: "), std::string::npos) << c.name;
  }
}

}  // namespace
}  // namespace rondo::store
