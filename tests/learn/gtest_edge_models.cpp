#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "rondo/learn/edge_models.h"
#include "series.h"

namespace rondo::learn {
namespace {

using testing::bursty_edge;
using testing::monday;

std::vector<Traversal> traversals(const std::string& edge, const std::vector<Attempt>& attempts) {
  std::vector<Traversal> out;
  for (const auto& a : attempts) {
    out.push_back({edge, "A", "B", a.start, from_seconds(a.seconds), a.success, ""});
  }
  return out;
}

std::shared_ptr<const EdgeModels> fitted() {
  auto log = traversals("A_B", bursty_edge(10));
  auto more = traversals("B_A", bursty_edge(10));
  log.insert(log.end(), more.begin(), more.end());
  const std::vector<EdgeSpec> edges = {{"A_B", 10.0}, {"B_A", 10.0}, {"B_C", 30.0}, {"C_B", 0.0}};
  auto models = EdgeModels::fit(edges, log);
  EXPECT_TRUE(models.ok());
  return *models;
}

TEST(EdgeModels, FitsEdgesWithDataAndPriorsForTheRest) {
  auto models = fitted();
  ASSERT_EQ(models->size(), 4u);
  EXPECT_TRUE(models->has_own_model(0));
  EXPECT_FALSE(models->has_own_model(2));
  EXPECT_EQ(models->attempts(0), 10 * 48 + 5 * 5);
  const Time t = monday() + hours(24 * 11 + 9);
  auto ab = models->estimate("A_B", t, std::vector<double>{0.1, 0.5, 0.9});
  ASSERT_TRUE(ab.ok());
  EXPECT_GT(ab->success_probability, 0.9);
  EXPECT_NEAR(ab->quantile_seconds[1], 12.0, 0.5);
  // B_C has no data: pooled success, its prior 30 s times the pooled actual/prior ratio (~1.2).
  auto bc = models->estimate("B_C", t, std::vector<double>{0.5});
  ASSERT_TRUE(bc.ok());
  EXPECT_NEAR(bc->quantile_seconds[0], 36.0, 1.0);
  // C_B has no data and no prior: the pooled durations.
  EXPECT_NEAR(models->quantile_seconds(3, t, 0.5), 12.0, 0.5);
}

TEST(EdgeModels, ErrorsNameTheEdge) {
  auto models = fitted();
  auto missing = models->estimate("X_Y", monday());
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().code, ErrorCode::kNotFound);
  EXPECT_NE(missing.error().message.find("X_Y"), std::string::npos);
  const std::vector<EdgeSpec> twice = {{"A_B", 1}, {"A_B", 2}};
  auto dup = EdgeModels::fit(twice, std::vector<Traversal>{});
  ASSERT_FALSE(dup.ok());
  EXPECT_NE(dup.error().message.find("A_B"), std::string::npos);
  EXPECT_FALSE(models->estimate("A_B", monday(), std::vector<double>{1.5}).ok());
}

TEST(EdgeModels, SaveAndLoadPredictTheSame) {
  auto models = fitted();
  const auto file = std::filesystem::temp_directory_path() / "rondo_gtest_edge_models.json";
  ASSERT_TRUE(models->save(file).ok());
  auto loaded = EdgeModels::load(file);
  std::filesystem::remove(file);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  ASSERT_EQ((*loaded)->size(), models->size());
  for (std::size_t e = 0; e < models->size(); ++e) {
    for (int h = 0; h < 24; h += 5) {
      const Time t = monday() + hours(24 * 11 + h);
      EXPECT_DOUBLE_EQ((*loaded)->success_probability(e, t), models->success_probability(e, t));
      EXPECT_DOUBLE_EQ((*loaded)->expected_seconds(e, t), models->expected_seconds(e, t));
      EXPECT_DOUBLE_EQ((*loaded)->quantile_seconds(e, t, 0.9), models->quantile_seconds(e, t, 0.9));
    }
  }
}

TEST(EdgeModels, LoadRejectsOtherDocuments) {
  const auto file = std::filesystem::temp_directory_path() / "rondo_gtest_not_models.json";
  { std::ofstream(file) << R"({"format": "something else"})"; }
  auto loaded = EdgeModels::load(file);
  std::filesystem::remove(file);
  ASSERT_FALSE(loaded.ok());
  EXPECT_NE(loaded.error().message.find(file.string()), std::string::npos);
  EXPECT_EQ(EdgeModels::load("/nonexistent/models.json").error().code, ErrorCode::kNotFound);
}

TEST(LiveEdgeModels, ConditionsOnTheLastOutcome) {
  auto models = fitted();
  LiveEdgeModels live(models);
  const Time t = monday() + hours(24 * 11 + 12);
  EXPECT_TRUE(live.observe(Traversal{"A_B", "A", "B", t, seconds(8), false, ""}));
  EXPECT_FALSE(live.observe(Traversal{"Q_R", "Q", "R", t, seconds(8), false, ""}));
  EXPECT_LT(live.success_probability(0, t + seconds(10)), 0.3);
  EXPECT_GT(live.success_probability(1, t + seconds(10)), 0.9);  // B_A saw nothing new
}

}  // namespace
}  // namespace rondo::learn
