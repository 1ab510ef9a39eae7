#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>

#include "rondo/learn/derived_series.h"
#include "rondo/learn/evaluation.h"
#include "series.h"
#include "witham.h"

namespace rondo::learn {
namespace {

using testing::day_night_series;

std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto file = std::filesystem::temp_directory_path() / name;
  std::ofstream(file) << text;
  return file;
}

TEST(ReadBinarySeries, ReadsAndSortsLines) {
  const auto file = write_temp("rondo_gtest_series.txt", "# door\n20 1\n10 0\n\n30 1 # open\n");
  auto series = read_binary_series(file);
  std::filesystem::remove(file);
  ASSERT_TRUE(series.ok()) << series.error().message;
  ASSERT_EQ(series->size(), 3u);
  EXPECT_EQ((*series)[0].time, from_unix_seconds(10));
  EXPECT_FALSE((*series)[0].value);
  EXPECT_TRUE((*series)[2].value);
}

TEST(ReadBinarySeries, ErrorsNameFileAndLine) {
  const char* bad[] = {"10 2\n", "10\n", "x 1\n", "10 1 7\n"};
  for (const char* text : bad) {
    const auto file = write_temp("rondo_gtest_bad_series.txt", std::string("5 1\n") + text);
    auto series = read_binary_series(file);
    std::filesystem::remove(file);
    ASSERT_FALSE(series.ok()) << text;
    EXPECT_EQ(series.error().code, ErrorCode::kInvalidInput);
    EXPECT_NE(series.error().message.find("rondo_gtest_bad_series.txt:2:"), std::string::npos)
        << series.error().message;
  }
}

TEST(EvaluateBinarySeries, ScoresEveryModelInBothProtocols) {
  auto all = day_night_series(21, 1800);
  const std::vector<BinarySample> train(all.begin(), all.begin() + 14 * 48);
  const std::vector<BinarySample> test(all.begin() + 14 * 48, all.end());
  auto result = evaluate_binary_series(train, test);
  ASSERT_TRUE(result.ok());
  EXPECT_EQ(result->test_samples, 7 * 48);
  double static_brier = 0, fremen_brier = 1, episode_brier = 1;
  for (const auto& row : result->models) {
    EXPECT_GE(row.brier, 0.0);
    EXPECT_LE(row.brier, 1.0);
    if (row.protocol != "offline" || row.train_dedup) continue;
    if (row.name == "static") static_brier = row.brier;
    if (row.name == "fremen-2") fremen_brier = row.brier;
    if (row.name == "episode") episode_brier = row.brier;
  }
  EXPECT_NEAR(static_brier, 0.25, 1e-9);
  EXPECT_LT(fremen_brier, 0.1);
  EXPECT_LT(episode_brier, 0.1);
  const Json j = evaluation_to_json(*result);
  EXPECT_TRUE(j["models"][0].contains("rmse"));
  EXPECT_FALSE(evaluate_binary_series({}, test).ok());
}

TEST(EvaluateBinarySeries, TheWeeklyRowLearnsAWeeklyClosure) {
  // Closed on Wednesday afternoons, otherwise open 95 % of the time: four weeks to learn, two to test.
  std::mt19937_64 rng(7);
  auto uniform = [&] { return std::uniform_real_distribution<double>(0.0, 1.0)(rng); };
  auto p = [](std::int64_t tow, std::int64_t) { return testing::wednesday_closure(tow, 0.95); };
  const auto all = testing::bernoulli_series(42, 1800, p, uniform);
  const std::vector<BinarySample> train(all.begin(), all.begin() + 28 * 48);
  const std::vector<BinarySample> test(all.begin() + 28 * 48, all.end());
  auto result = evaluate_binary_series(train, test);
  ASSERT_TRUE(result.ok());
  std::map<std::string, double> offline;
  int weekly_rows = 0;
  for (const auto& row : result->models) {
    if (row.name == "episode-week") ++weekly_rows;
    if (row.protocol == "offline" && !row.train_dedup) offline[row.name] = row.brier;
  }
  EXPECT_EQ(weekly_rows, 2);  // offline and online
  EXPECT_LT(offline.at("episode-week"), offline.at("episode") - 0.005);
}

TEST(EvaluateEdges, NoEdgePassingTheFilterIsAnError) {
  auto result = evaluate_edges({}, {.split = testing::monday()});
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().code, ErrorCode::kInvalidInput);
}

// Issue 3's default split: the filter, and our model ahead of FreMEn in both protocols.
TEST(EvaluateEdges, WithamWharfDefaultSplit) {
  auto log = read_witham_logs(testing::kWithamDir);
  if (!log) GTEST_SKIP() << "no Witham Wharf data at " << testing::kWithamDir;
  auto result = evaluate_edges(*log, {.split = *parse_time("2014-09-02T16:24:00Z")});
  ASSERT_TRUE(result.ok()) << result.error().message;
  EXPECT_EQ(result->edges, 40);
  EXPECT_EQ(result->test_attempts, 9009);
  double best_fremen_offline = 1, episode_offline = 1, episode_online = 1;
  for (const auto& row : result->models) {
    if (row.name.starts_with("fremen") && row.protocol == "offline")
      best_fremen_offline = std::min(best_fremen_offline, row.brier);
    if (row.name == "episode") (row.protocol == "offline" ? episode_offline : episode_online) = row.brier;
  }
  EXPECT_LT(episode_offline, best_fremen_offline);
  EXPECT_LT(episode_offline, 0.1011);
  EXPECT_LE(episode_online, 0.060);
  const Json j = evaluation_to_json(*result);
  EXPECT_EQ(j["edges"], 40);
  EXPECT_EQ(j["test_attempts"], 9009);
}

// A validation split inside the training period: nothing at or after `until` is read.
TEST(EvaluateEdges, UntilKeepsTheEvaluationInsideAPeriod) {
  auto log = read_witham_logs(testing::kWithamDir);
  if (!log) GTEST_SKIP() << "no Witham Wharf data at " << testing::kWithamDir;
  EdgeEvalOptions options;
  options.split = *parse_time("2014-08-20T00:00:00Z");
  options.until = *parse_time("2014-09-02T16:24:00Z");
  auto result = evaluate_edges(*log, options);
  ASSERT_TRUE(result.ok()) << result.error().message;
  std::map<std::string, std::pair<int, int>> counts;  // train, test per edge
  for (const auto& t : *log) {
    if (t.start >= *options.until) continue;
    auto& c = counts[t.edge_id];
    (t.start < options.split ? c.first : c.second) += 1;
  }
  int edges = 0, test = 0;
  for (const auto& [id, c] : counts) {
    if (c.first >= 20 && c.second >= 5) {
      ++edges;
      test += c.second;
    }
  }
  EXPECT_EQ(result->edges, edges);
  EXPECT_EQ(result->test_attempts, test);
  EXPECT_GT(test, 0);
}

// Derived series: the robot's position from a small hand-made log.
TEST(DerivedSeries, PresenceAndArrivalsFollowTheLog) {
  const Time t0 = testing::monday();
  const std::vector<Traversal> log = {
      {"A_K", "A", "K", t0 + minutes(5), seconds(60), true, ""},      // arrives at K in slot 0
      {"K_A", "K", "A", t0 + minutes(70), seconds(60), false, ""},    // fails: still at K
      {"K_A", "K", "A", t0 + minutes(130), seconds(60), true, ""},    // leaves K in slot 2
      {"A_K", "A", "K", t0 + minutes(200), seconds(30), false, ""}};  // a failed try in slot 3
  const auto arrivals = arrivals_in_slot(log, "K", t0, t0 + hours(4), hours(1));
  ASSERT_EQ(arrivals.size(), 4u);
  EXPECT_TRUE(arrivals[0].value);
  EXPECT_FALSE(arrivals[1].value);
  EXPECT_FALSE(arrivals[2].value);
  EXPECT_FALSE(arrivals[3].value);
  EXPECT_EQ(arrivals[2].time, t0 + hours(2));
  const auto at_k = presence_at_node(log, "K", t0, t0 + hours(4), hours(1));
  ASSERT_EQ(at_k.size(), 4u);
  EXPECT_FALSE(at_k[0].value);  // 00:00: nothing has happened yet
  EXPECT_TRUE(at_k[1].value);   // 01:00: arrived at 00:06
  EXPECT_FALSE(at_k[2].value);  // 02:00: the latest traversal is the failed K_A, not an arrival at K
  EXPECT_FALSE(at_k[3].value);  // 03:00: left at 02:10
  EXPECT_TRUE(arrivals_in_slot(log, "K", t0, t0 + hours(1), seconds(0)).empty());
}

}  // namespace
}  // namespace rondo::learn
