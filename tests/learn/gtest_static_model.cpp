#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <numeric>

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

TEST(OnlineStaticDuration, StartsAtThePriorAndMovesToTheSamples) {
  OnlineStaticDuration d(60, 2);
  EXPECT_DOUBLE_EQ(d.expected_seconds(monday()), 60);
  EXPECT_DOUBLE_EQ(d.quantile_seconds(monday(), 0.9), 60);  // the prior alone before a sample
  d.observe(monday(), 300, true);
  EXPECT_DOUBLE_EQ(d.expected_seconds(monday()), (2 * 60 + 300) / 3.0);
  d.observe(monday(), 900, false);  // a failure says nothing of how long a success takes
  EXPECT_DOUBLE_EQ(d.expected_seconds(monday()), (2 * 60 + 300) / 3.0);
  EXPECT_EQ(d.samples(), 1u);
  for (int i = 0; i < 200; ++i) d.observe(monday(), 300, true);
  EXPECT_NEAR(d.expected_seconds(monday()), (2 * 60 + 201 * 300) / 203.0, 1e-9);
  EXPECT_DOUBLE_EQ(d.quantile_seconds(monday(), 0.5), 300);
}

TEST(OnlineStaticDuration, AStoppedRunCountsAsItsLengthPlusTheTimeStillExpected) {
  OnlineStaticDuration d(60, 2);
  d.observe_stopped(monday(), 90);  // at least 90 s: counted as 90 + the current mean 60
  EXPECT_DOUBLE_EQ(d.expected_seconds(monday()), (2 * 60 + 150) / 3.0);
  EXPECT_EQ(d.samples(), 1u);
  d.observe_stopped(monday(), -1);  // nonsense is ignored
  EXPECT_EQ(d.samples(), 1u);
  OnlineStaticDuration as_sample(60, 2);
  as_sample.observe(monday(), 90, true);
  EXPECT_GT(d.expected_seconds(monday()), as_sample.expected_seconds(monday()));  // 90 s against 70 s
}

// The running mean with a prior equals the obviously correct sum over everything seen, and the
// quantiles are those of the last `window` successes.
RC_GTEST_PROP(OnlineStaticDuration, IsTheMeanWithItsPriorAndTheQuantilesOfTheWindow, ()) {
  const auto values = *rc::gen::container<std::vector<int>>(rc::gen::inRange(0, 5000));
  const std::size_t window = *rc::gen::inRange<std::size_t>(1, 20);
  OnlineStaticDuration d(100, 3, window);
  for (int v : values) d.observe(monday(), v, true);
  const double sum = std::accumulate(values.begin(), values.end(), 0.0);
  RC_ASSERT(std::abs(d.expected_seconds(monday()) - (300 + sum) / (3.0 + static_cast<double>(values.size()))) < 1e-6);
  if (values.empty()) return;
  std::vector<double> last;
  for (std::size_t i = values.size() > window ? values.size() - window : 0; i < values.size(); ++i)
    last.push_back(values[i]);
  const QuantileTable q = QuantileTable::from_samples(last);
  for (double level : {0.1, 0.5, 0.9}) RC_ASSERT(std::abs(d.quantile_seconds(monday(), level) - q.at(level)) < 1e-9);
}

}  // namespace
}  // namespace rondo::learn
