// `rondo eval` and `rondo learn`, run in-process.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/cli_runner.h"
#include "rondo/core/document.h"
#include "rondo/learn/edge_models.h"
#include "witham.h"

namespace rondo::learn {
namespace {

using rondo::test::run_cli;

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto file = std::filesystem::temp_directory_path() / name;
  std::ofstream(file) << text;
  return file;
}

TEST(EvalCommand, BinarySeriesAsJson) {
  std::string train, test;
  for (int i = 0; i < 24 * 14; ++i)
    train += std::to_string(1404691200 + 3600 * i) + (i % 24 >= 8 && i % 24 < 20 ? " 1\n" : " 0\n");
  for (int i = 24 * 14; i < 24 * 21; ++i)
    test += std::to_string(1404691200 + 3600 * i) + (i % 24 >= 8 && i % 24 < 20 ? " 1\n" : " 0\n");
  const auto train_file = write_temp("rondo_cli_train.txt", train);
  const auto test_file = write_temp("rondo_cli_test.txt", test);
  auto r = run_cli({"eval", "binary", "--train", train_file.string(), "--test", test_file.string(), "--json"});
  std::filesystem::remove(train_file);
  std::filesystem::remove(test_file);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  ASSERT_TRUE(j["models"].is_array());
  for (const auto& m : j["models"]) {
    EXPECT_TRUE(m.contains("name") && m.contains("protocol") && m.contains("rmse") && m.contains("brier"));
  }
}

TEST(EvalCommand, BadInputExitsWithTwo) {
  EXPECT_EQ(run_cli({"eval", "binary", "--train", "/nonexistent/a", "--test", "/nonexistent/b"}).exit_code, 2);
  auto r = run_cli({"eval", "edges", "--witham", testing::kWithamDir, "--split", "yesterday"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--split"), std::string::npos) << r.err;
  EXPECT_EQ(run_cli({"eval", "edges", "--witham", "/nonexistent"}).exit_code, 2);
}

TEST(EvalCommand, WithamEdgesJsonShape) {
  if (!std::filesystem::is_directory(testing::kWithamDir)) GTEST_SKIP() << "no Witham Wharf data";
  auto r = run_cli({"eval", "edges", "--witham", testing::kWithamDir, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["edges"], 40);
  EXPECT_EQ(j["test_attempts"], 9009);
  bool saw_dedup_fremen = false;
  for (const auto& m : j["models"]) {
    for (const char* key : {"name", "protocol", "train_dedup", "brier", "binary_error", "duration_mae"}) {
      EXPECT_TRUE(m.contains(key)) << key;
    }
    saw_dedup_fremen = saw_dedup_fremen || (m["name"] == "fremen-2" && m["train_dedup"] == true);
  }
  EXPECT_TRUE(saw_dedup_fremen);
}

TEST(LearnCommand, MissingDatabaseIsBadInput) {
  const auto out = std::filesystem::temp_directory_path() / "rondo_cli_models.json";
  EXPECT_EQ(run_cli({"learn", "--db", "/nonexistent/rondo.db", "-o", out.string()}).exit_code, 2);
}

TEST(LearnCommand, FitsWhatTheLogImported) {
  if (!std::filesystem::is_directory(testing::kWithamDir)) GTEST_SKIP() << "no Witham Wharf data";
  const auto dir = std::filesystem::temp_directory_path() / "rondo_cli_learn";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto db = (dir / "rondo.db").string();
  const auto models = (dir / "models.json").string();
  auto imported = run_cli({"log", "import", "--witham", testing::kWithamDir, "--db", db});
  ASSERT_EQ(imported.exit_code, 0) << imported.err;
  auto learned = run_cli({"learn", "--db", db, "-o", models});
  ASSERT_EQ(learned.exit_code, 0) << learned.err;
  auto loaded = EdgeModels::load(models);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  EXPECT_EQ((*loaded)->size(), 62u);
  std::filesystem::remove_all(dir);
}

// Imports the Witham Wharf log into a fresh database in `dir`; the database path.
std::string witham_db(const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto db = (dir / "rondo.db").string();
  auto imported = run_cli({"log", "import", "--witham", testing::kWithamDir, "--db", db});
  EXPECT_EQ(imported.exit_code, 0) << imported.err;
  return db;
}

TEST(LearnCommand, WithAMapLearnsItsEdgesWithDistancePriors) {
  if (!std::filesystem::is_directory(testing::kWithamDir)) GTEST_SKIP() << "no Witham Wharf data";
  const auto dir = std::filesystem::temp_directory_path() / "rondo_cli_learn_map";
  const auto db = witham_db(dir);
  const auto models = (dir / "models.json").string();
  auto learned = run_cli({"learn", "--db", db, "--map", (rondo::testing::source_dir() / "examples/witham/map.yaml").string(), "--zone",
                          "Europe/London", "-o", models, "--json"});
  ASSERT_EQ(learned.exit_code, 0) << learned.err;
  const Json summary = Json::parse(learned.out);
  EXPECT_EQ(summary["edges"], 62);
  EXPECT_EQ(summary["traversals_of_unknown_edges"], 0);
  auto loaded = EdgeModels::load(models);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ((*loaded)->size(), 62u);
  for (std::size_t e = 0; e < (*loaded)->size(); ++e) {
    EXPECT_GT((*loaded)->spec(e).prior_seconds, 0.0) << (*loaded)->spec(e).id;  // the map's distance prior
  }
  EXPECT_EQ((*loaded)->to_json()["priors"]["time_zone"], "Europe/London");
  std::filesystem::remove_all(dir);
}

TEST(LearnCommand, MapEdgesWithoutDataGetThePriorModel) {
  if (!std::filesystem::is_directory(testing::kWithamDir)) GTEST_SKIP() << "no Witham Wharf data";
  const auto dir = std::filesystem::temp_directory_path() / "rondo_cli_learn_other_map";
  const auto db = witham_db(dir);
  const auto models = (dir / "models.json").string();
  // A map of another building: no edge id matches the log.
  auto learned =
      run_cli({"learn", "--db", db, "--map", (rondo::testing::source_dir() / "tests/data/maps/small.yaml").string(), "-o", models, "--json"});
  ASSERT_EQ(learned.exit_code, 0) << learned.err;
  const Json summary = Json::parse(learned.out);
  EXPECT_EQ(summary["edges_with_own_model"], 0);
  EXPECT_EQ(summary["traversals_of_unknown_edges"], summary["traversals"]);
  auto loaded = EdgeModels::load(models);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_GT((*loaded)->size(), 0u);
  const Time t = *parse_time("2014-09-03T10:00:00Z");
  for (std::size_t e = 0; e < (*loaded)->size(); ++e) {
    EXPECT_FALSE((*loaded)->has_own_model(e));
    // No edge has both data and a prior, so the pooled actual/prior ratio is unknown: the
    // distance-based prior itself.
    EXPECT_GT((*loaded)->spec(e).prior_seconds, 0.0);
    EXPECT_DOUBLE_EQ((*loaded)->expected_seconds(e, t), (*loaded)->spec(e).prior_seconds);
    EXPECT_DOUBLE_EQ((*loaded)->quantile_seconds(e, t, 0.9), (*loaded)->spec(e).prior_seconds);
  }
  std::filesystem::remove_all(dir);
}

TEST(LearnCommand, BadMapOrZoneIsBadInput) {
  // Both are checked before the database is opened.
  const auto models = (std::filesystem::temp_directory_path() / "rondo_cli_models.json").string();
  auto no_map = run_cli({"learn", "--db", "/nonexistent/rondo.db", "--map", "/nonexistent/map.yaml", "-o", models});
  auto no_zone = run_cli({"learn", "--db", "/nonexistent/rondo.db", "--zone", "Mars/Olympus_Mons", "-o", models});
  EXPECT_EQ(no_map.exit_code, 2) << no_map.err;
  EXPECT_NE(no_map.err.find("--map"), std::string::npos) << no_map.err;
  EXPECT_NE(no_map.err.find("/nonexistent/map.yaml"), std::string::npos) << no_map.err;
  EXPECT_EQ(no_zone.exit_code, 2) << no_zone.err;
  EXPECT_NE(no_zone.err.find("--zone"), std::string::npos) << no_zone.err;
}

}  // namespace
}  // namespace rondo::learn
