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

// 50 episodes of one 20 s success; 10 failed episodes of a 5 s failure and one 5 s retry; and one
// failed episode of a 5 s failure followed by a storm of 500 retries of 0.5 s.
std::vector<Attempt> storm_edge() {
  std::vector<Attempt> out;
  Time t = monday();
  for (int i = 0; i < 50; ++i, t += hours(1)) out.push_back({t, t + seconds(20), 20.0, true});
  for (int i = 0; i < 10; ++i, t += hours(1)) {
    out.push_back({t, t + seconds(5), 5.0, false});
    out.push_back({t + seconds(7), t + seconds(12), 5.0, false});
  }
  out.push_back({t, t + seconds(5), 5.0, false});
  t += seconds(7);
  for (int i = 0; i < 500; ++i, t += seconds(2)) out.push_back({t, t + milliseconds(500), 0.5, false});
  return out;
}

TEST(EpisodeModel, ARetryStormWeighsLikeOneTypicalEpisodeOffline) {
  EpisodeOptions options;
  options.duration_half_life = seconds(0);
  options.day_resolutions = {1};  // one bin: the whole day
  auto fit = fit_episode_models({storm_edge()}, options);
  const auto& model = *fit.edges[0];
  // Counted per attempt, 500 of 571 attempts take 0.5 s and so would the median. Counted by
  // episodes, the storm holds about L − 1 ≈ 1.8 retries' weight (L: the shrunk geometric mean
  // episode length) of ~81: the median lies between the 5 s failures and the 20 s successes.
  EXPECT_GT(model.quantile_seconds(monday(), 0.5), 10.0);
  EXPECT_LE(model.quantile_seconds(monday(), 0.5), 20.0);
  EXPECT_LT(model.quantile_seconds(monday(), 0.02), 1.0);  // the storm is still in the table
}

TEST(EpisodeModel, OfflineDurationsFollowRecentAttempts) {
  std::vector<Attempt> attempts;
  for (int d = 0; d < 60; ++d) {
    const Time t = monday() + hours(24 * d + 10);
    const double secs = d < 30 ? 10.0 : 30.0;
    attempts.push_back({t, t + from_seconds(secs), secs, true});
  }
  EpisodeOptions no_decay;
  no_decay.duration_half_life = seconds(0);
  no_decay.day_resolutions = {1};
  EpisodeOptions decay = no_decay;
  decay.duration_half_life = std::chrono::days(7);
  const Time later = monday() + hours(24 * 61 + 10);
  const double flat = fit_episode_models({attempts}, no_decay).edges[0]->quantile_seconds(later, 0.5);
  const double recent = fit_episode_models({attempts}, decay).edges[0]->quantile_seconds(later, 0.5);
  // Two point masses, interpolated between their share centres: equal shares put the median
  // half way; with decay the last 30 days hold 1 − 2^(−30/7) ≈ 95 % of the weight.
  EXPECT_NEAR(flat, 20.0, 1e-9);
  EXPECT_GT(recent, 28.0);
  EXPECT_LE(recent, 30.0);
}

TEST(EpisodeModel, MixtureShrinkageKeepsTheModesOfEdgeAndPool) {
  // Edge 0: three 10 s crossings; edge 1: 200 crossings of 100 s. The pooled table (each edge
  // weighs 1) is half 10 s, half 100 s; edge 0 is shrunk towards it with n / (n + 10) ≈ 0.23.
  std::vector<std::vector<Attempt>> edges(2);
  for (int d = 0; d < 200; ++d) {
    const Time t = monday() + hours(24 * d + 10);
    if (d < 3) edges[0].push_back({t, t + seconds(10), 10.0, true});
    edges[1].push_back({t, t + seconds(100), 100.0, true});
  }
  EpisodeOptions average;
  average.duration_half_life = seconds(0);
  average.duration_mixture = false;
  EpisodeOptions mixture = average;
  mixture.duration_mixture = true;
  const Time at = monday() + hours(10);
  const auto blended_fit = fit_episode_models(edges, average);
  const auto mixed_fit = fit_episode_models(edges, mixture);
  const auto& blended = *blended_fit.edges[0];
  const auto& mixed = *mixed_fit.edges[0];
  // Quantile averaging invents durations between the modes (0.23·10 + 0.77·55 at the median) ...
  EXPECT_GT(blended.quantile_seconds(at, 0.5), 30.0);
  EXPECT_LT(blended.quantile_seconds(at, 0.98), 90.0);
  // ... a mixture keeps ~62 % at 10 s and ~38 % at 100 s.
  EXPECT_NEAR(mixed.quantile_seconds(at, 0.3), 10.0, 1e-3);
  EXPECT_NEAR(mixed.quantile_seconds(at, 0.5), 10.0, 1e-3);
  EXPECT_NEAR(mixed.quantile_seconds(at, 0.9), 100.0, 1e-3);
  // The option travels with the model.
  auto round_trip = EpisodePriors::from_json(mixed_fit.priors->to_json());
  ASSERT_TRUE(round_trip) << round_trip.error().message;
  EXPECT_TRUE(round_trip->options.duration_mixture);
  // Files written before the option existed were fitted with quantile averaging.
  Json older = mixed_fit.priors->to_json();
  older.erase("duration_mixture");
  auto loaded = EpisodePriors::from_json(older);
  ASSERT_TRUE(loaded) << loaded.error().message;
  EXPECT_FALSE(loaded->options.duration_mixture);
}

TEST(EpisodeModel, MixedShiftedHistogramsKeepEachTimeOfDaysModes) {
  // 10 s crossings at 09:00 and 100 s crossings at 21:00 (UTC), 100 days of each. Histograms of 1
  // and of 2 bins a day (4 shifts of 3 h): at 09:00 one histogram of 5 (the whole day) is half
  // 100 s, the four 12-hour bins hold 10 s only; a mixture keeps ~85 % of the slot at exactly
  // 10 s and the 100 s mode in its top few per cent, where quantile averaging would move the whole
  // slot towards 55 s. 21:00 is the mirror image (and must not share 09:00's table).
  std::vector<Attempt> attempts;
  for (int d = 0; d < 100; ++d) {
    const Time morning = monday() + hours(24 * d + 9);
    const Time evening = monday() + hours(24 * d + 21);
    attempts.push_back({morning, morning + seconds(10), 10.0, true});
    attempts.push_back({evening, evening + seconds(100), 100.0, true});
  }
  EpisodeOptions mixture;
  mixture.duration_half_life = seconds(0);
  mixture.day_resolutions = {1, 2};
  mixture.duration_prior = 1e-9;  // every bin is its own data
  EpisodeOptions average = mixture;
  average.duration_mixture = false;
  const auto mixed_fit = fit_episode_models({attempts}, mixture);
  const auto averaged_fit = fit_episode_models({attempts}, average);
  const auto& mixed = *mixed_fit.edges[0];
  const Time nine = monday() + hours(9), twenty_one = monday() + hours(21);
  EXPECT_DOUBLE_EQ(mixed.quantile_seconds(nine, 0.02), 10.0);
  EXPECT_DOUBLE_EQ(mixed.quantile_seconds(nine, 0.8), 10.0);
  EXPECT_GT(mixed.quantile_seconds(nine, 0.9), 10.0);
  EXPECT_DOUBLE_EQ(mixed.quantile_seconds(nine, 0.98), 100.0);
  EXPECT_DOUBLE_EQ(mixed.quantile_seconds(twenty_one, 0.02), 10.0);
  EXPECT_DOUBLE_EQ(mixed.quantile_seconds(twenty_one, 0.2), 100.0);
  EXPECT_DOUBLE_EQ(mixed.quantile_seconds(twenty_one, 0.98), 100.0);
  EXPECT_GT(averaged_fit.edges[0]->quantile_seconds(nine, 0.5), 15.0);
}

TEST(EpisodePriors, TimeOfDayIsLocalTimeInTheZone) {
  EpisodePriors utc;
  EpisodePriors london;
  london.options.zone = *TimeZone::named("Europe/London");
  const Time summer_nine = *parse_time("2014-07-08T08:00:00Z");  // 09:00 British summer time
  const Time winter_nine = *parse_time("2014-12-08T09:00:00Z");  // 09:00 GMT
  EXPECT_EQ(london.day_slot(summer_nine), 36);
  EXPECT_EQ(london.day_slot(winter_nine), 36);
  EXPECT_EQ(utc.day_slot(summer_nine), 32);
  EXPECT_EQ(utc.day_slot(winter_nine), 36);
  EXPECT_EQ(london.duration_bin(summer_nine), london.duration_bin(winter_nine));
}

TEST(EpisodeModel, JsonKeepsTheTimeZone) {
  std::vector<BinarySample> samples;
  for (const auto& a : bursty_edge(10)) samples.push_back({a.start, a.success});
  EpisodeOptions options;
  options.zone = *TimeZone::named("Europe/London");
  Json j = fit_episode_binary(samples, options)->to_json();
  EXPECT_EQ(j["priors"]["time_zone"], "Europe/London");
  auto back = EpisodePriors::from_json(j["priors"]);
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(back->options.zone.name(), "Europe/London");
  j["priors"]["time_zone"] = "Mars/Olympus_Mons";
  auto bad = binary_model_from_json(j);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("time_zone"), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("Mars/Olympus_Mons"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace rondo::learn
