#include <gtest/gtest.h>

#include "rondo/learn/model_json.h"
#include "rondo/learn/quantile_table.h"
#include "rondo/learn/static_model.h"
#include "series.h"

namespace rondo::learn {
namespace {

using testing::monday;

TEST(StaticModel, BinaryIsTheFractionOfTrueSamples) {
  struct Case {
    std::vector<bool> values;
    double expected;
  };
  const Case cases[] = {{{}, 0.5}, {{true}, 1.0}, {{false}, 0.0}, {{true, false, true, true}, 0.75}};
  for (const auto& c : cases) {
    std::vector<BinarySample> samples;
    for (bool v : c.values) samples.push_back({monday() + seconds(static_cast<std::int64_t>(samples.size())), v});
    EXPECT_DOUBLE_EQ(fit_static_binary(samples)->probability(monday()), c.expected);
  }
}

TEST(StaticModel, DurationMeanAndQuantiles) {
  std::vector<DurationSample> samples;
  for (int i = 1; i <= 101; ++i) samples.push_back({monday() + seconds(i), static_cast<double>(i)});
  auto model = fit_static_duration(samples);
  EXPECT_DOUBLE_EQ(model->expected_seconds(monday()), 51.0);
  EXPECT_NEAR(model->quantile_seconds(monday(), 0.5), 51.0, 1e-9);
  EXPECT_NEAR(model->quantile_seconds(monday(), 0.9), 91.0, 1e-9);
}

TEST(StaticModel, JsonRoundTrip) {
  auto binary = binary_model_from_json(StaticBinaryModel(0.25).to_json());
  ASSERT_TRUE(binary.ok()) << binary.error().message;
  EXPECT_DOUBLE_EQ((*binary)->probability(monday()), 0.25);

  auto fitted = fit_static_duration(std::vector<DurationSample>{{monday(), 3.0}, {monday(), 5.0}});
  auto duration = duration_model_from_json(fitted->to_json());
  ASSERT_TRUE(duration.ok()) << duration.error().message;
  EXPECT_DOUBLE_EQ((*duration)->expected_seconds(monday()), 4.0);
  EXPECT_DOUBLE_EQ((*duration)->quantile_seconds(monday(), 0.3), fitted->quantile_seconds(monday(), 0.3));
}

TEST(StaticModel, BadJsonIsAnError) {
  const char* bad[] = {R"({"mean": 0.5})", R"({"type": "static"})", R"({"type": "static", "mean": 2})",
                       R"({"type": "nope"})", R"([1, 2])"};
  for (const char* text : bad) {
    EXPECT_FALSE(binary_model_from_json(Json::parse(text)).ok()) << text;
  }
}

TEST(QuantileTable, InterpolatesOrderStatistics) {
  auto table = QuantileTable::from_samples({4.0, 1.0, 3.0, 2.0, 5.0});
  EXPECT_NEAR(table.at(0.5), 3.0, 1e-12);
  EXPECT_NEAR(table.at(0.02), 1.08, 1e-12);
  EXPECT_NEAR(table.at(0.0), table.at(0.02), 1e-12);  // no extrapolation
  EXPECT_NEAR(table.at(1.0), table.at(0.98), 1e-12);
  EXPECT_DOUBLE_EQ(QuantileTable::from_samples({-3.0}).at(0.5), 0.0);
  EXPECT_DOUBLE_EQ(QuantileTable::from_samples({-3.0}, true).at(0.5), -3.0);
}

TEST(QuantileTable, FromJsonRejectsBadTables) {
  EXPECT_FALSE(QuantileTable::from_json(Json::array({1, 2, 3})).ok());
  Json decreasing = QuantileTable::from_samples({1.0, 2.0}).to_json();
  decreasing[3] = -1.0;
  EXPECT_FALSE(QuantileTable::from_json(decreasing).ok());
}

}  // namespace
}  // namespace rondo::learn
