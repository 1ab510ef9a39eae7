#include <gtest/gtest.h>

#include <cmath>

#include "rondo/learn/episode_model.h"
#include "rondo/learn/model_json.h"
#include "series.h"

namespace rondo::learn {
namespace {

using testing::bursty_edge;
using testing::monday;

TEST(EpisodeStats, StatesBucketTheGapOnALogScale) {
  struct Case {
    bool last_success;
    double gap_s;
    int state;
  };
  const Case cases[] = {{false, 0, 0},  {false, 3.9, 0}, {false, 4, 1},   {false, 12, 2},
                        {false, 59, 3}, {true, 0, 13},   {true, 1e9, 25}, {false, -5, 0}};
  for (const auto& c : cases) {
    EXPECT_EQ(EpisodeStats::state_of(c.last_success, from_seconds(c.gap_s)), c.state) << c.gap_s;
  }
}

TEST(EpisodeModel, CountsEpisodesAndRetries) {
  auto fit = fit_episode_models({bursty_edge(10)});
  const EpisodeStats& s = fit.edges[0]->stats();
  EXPECT_DOUBLE_EQ(s.failed_episodes, 5);  // one burst every second day
  EXPECT_NEAR(std::exp(s.log_length_sum / s.failed_episodes), 6.0, 1e-9);
  double first = 0;
  for (double n : s.first_attempts) first += n;
  EXPECT_DOUBLE_EQ(first, 480);  // 48 episodes a day
}

TEST(EpisodeModel, OfflineProbabilityCountsTheRetriesAFailureBrings) {
  auto fit = fit_episode_models({bursty_edge(20)});
  const auto& model = *fit.edges[0];
  const Time noon = monday() + hours(24 * 30 + 12) + minutes(5);
  const Time morning = monday() + hours(24 * 30 + 6);
  EXPECT_GT(model.probability(morning), 0.9);
  // Around noon first attempts fail half the time and each failure brings 5 more failed attempts.
  EXPECT_LT(model.probability(noon), model.probability(morning));
  EXPECT_GT(model.retry_length(model.stats()), 3.0);
}

TEST(EpisodeModel, OnlineFollowsTheBurst) {
  auto fit = fit_episode_models({bursty_edge(20)});
  EpisodePredictor live(fit.edges[0]);
  const Time t = monday() + hours(24 * 40 + 12);
  live.observe({t, t + seconds(8), 8.0, false});
  EXPECT_LT(live.probability(t + seconds(10)), 0.2);  // a retry 2 s after a failure
  EXPECT_NEAR(live.quantile_seconds(t + seconds(10), 0.5), 8.0, 1.0);
  live.observe({t + seconds(10), t + seconds(22), 12.0, true});
  EXPECT_GT(live.probability(t + minutes(30)), 0.9);
}

TEST(EpisodeModel, JsonRoundTripPredictsTheSame) {
  std::vector<BinarySample> samples;
  for (const auto& a : bursty_edge(10)) samples.push_back({a.start, a.success});
  auto model = fit_episode_binary(samples);
  auto back = binary_model_from_json(model->to_json());
  ASSERT_TRUE(back.ok()) << back.error().message;
  for (int m = 0; m < 24 * 60; m += 37) {
    const Time t = monday() + hours(24 * 12) + minutes(m);
    EXPECT_DOUBLE_EQ((*back)->probability(t), model->probability(t));
  }
}

TEST(EpisodeModel, AnEdgeWithoutDataGetsThePooledRates) {
  auto fit = fit_episode_models({bursty_edge(10), {}});
  const auto& empty = *fit.edges[1];
  const double p = empty.probability(monday());
  EXPECT_GT(p, 0.5);
  EXPECT_LE(p, 1.0);
  EXPECT_GT(empty.quantile_seconds(monday(), 0.5), 0.0);  // pooled durations
}

TEST(EpisodeModel, NonsenseBinCountsAreClampedNotFatal) {
  EpisodeOptions options;
  options.duration_bins = 0;
  options.day_resolutions = {0, 5, 6};  // 0 and 5 do not divide 24: ignored
  auto fit = fit_episode_models({bursty_edge(4)}, options);
  EXPECT_EQ(fit.priors->options.duration_bins, 1);
  EXPECT_NEAR(fit.edges[0]->quantile_seconds(monday(), 0.5), 12.0, 0.5);
  const double p = fit.edges[0]->probability(monday());
  EXPECT_GE(p, 0.0);
  EXPECT_LE(p, 1.0);
}

}  // namespace
}  // namespace rondo::learn
