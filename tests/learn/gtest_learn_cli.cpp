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

}  // namespace
}  // namespace rondo::learn
