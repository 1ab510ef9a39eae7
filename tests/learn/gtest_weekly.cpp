// The time-of-week term of the episode model (issue 19): it is learned where the data have a
// weekly pattern, left out where they have none, chosen deterministically, and both the choice
// and q(t) agree with slow, obviously correct forms of their definitions.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <random>

#include "histogram_family.h"
#include "rondo/learn/edge_models.h"
#include "rondo/learn/episode_model.h"
#include "rondo/learn/model_json.h"
#include "series.h"

namespace rondo::learn {
namespace {

using testing::bernoulli_series;
using testing::monday;

// A deterministic uniform source for the series, seeded by the property's generated seed.
struct Uniform {
  explicit Uniform(std::uint64_t seed) : rng(seed) {}
  double operator()() { return std::uniform_real_distribution<double>(0.0, 1.0)(rng); }
  std::mt19937_64 rng;
};

// The mean over every 15 minutes of a week of (q(t) − p(t))²: a model's Brier score minus the
// noise floor E[p(1 − p)], exactly (no test noise). `p` takes seconds since Monday 00:00 UTC.
template <class P>
double excess_brier(const BinaryModel& model, P&& p, Time week_start) {
  double sum = 0;
  for (int slot = 0; slot < kWeekSlots; ++slot) {
    const std::int64_t s = std::int64_t{slot} * 900 + 450;
    const double e = model.probability(week_start + seconds(s)) - p(s);
    sum += e * e;
  }
  return sum / kWeekSlots;
}

EpisodeOptions with_weekly(WeeklyTerm w) {
  EpisodeOptions o;
  o.weekly = w;
  return o;
}

// Success probability by day of the week (Monday first), with at least one large difference.
rc::Gen<std::array<double, 7>> gen_week_levels() {
  return rc::gen::suchThat(rc::gen::map(rc::gen::container<std::vector<int>>(7, rc::gen::inRange(1, 20)),
                                        [](const std::vector<int>& v) {
                                          std::array<double, 7> out{};
                                          for (std::size_t d = 0; d < 7; ++d) out[d] = v[d] / 20.0;
                                          return out;
                                        }),
                           [](const std::array<double, 7>& l) {
                             return *std::max_element(l.begin(), l.end()) - *std::min_element(l.begin(), l.end()) >=
                                    0.5;
                           });
}

RC_GTEST_PROP(Weekly, APureWeeklyPatternIsLearned, ()) {
  const auto levels = *gen_week_levels();
  Uniform uniform(*rc::gen::arbitrary<std::uint64_t>());
  auto p = [&](std::int64_t tow, std::int64_t = 0) { return levels[static_cast<std::size_t>(tow / 86400)]; };
  double mean = 0;
  for (double l : levels) mean += l / 7;
  double between_days = 0;  // what a model of the time of day alone cannot remove
  for (double l : levels) between_days += (l - mean) * (l - mean) / 7;
  const auto few = bernoulli_series(14, 1800, p, uniform);
  const auto many = bernoulli_series(16 * 7, 1800, p, uniform);
  const auto weekly_few = fit_episode_binary(few);
  const auto weekly_many = fit_episode_binary(many);
  const auto daily_many = fit_episode_binary(many, with_weekly(WeeklyTerm::kOff));
  RC_ASSERT(weekly_many->model().weekly().weekly);
  const Time next_week = monday() + hours(24 * 7 * 16);
  const double e_few = excess_brier(*weekly_few, p, next_week);
  const double e_many = excess_brier(*weekly_many, p, next_week);
  const double e_daily = excess_brier(*daily_many, p, next_week);
  RC_LOG() << "excess 2 weeks " << e_few << ", 16 weeks " << e_many << ", daily " << e_daily << ", between days "
           << between_days << "\n";
  // The day-only model keeps the between-day variance; the weekly term removes most of it (what is
  // left is the shifted bins that straddle midnight), and more data brings it closer to the floor.
  RC_ASSERT(e_daily >= 0.8 * between_days);
  RC_ASSERT(e_many <= 0.25 * between_days);
  RC_ASSERT(e_many <= e_few + 1e-9);
}

RC_GTEST_PROP(Weekly, NoWeeklyPatternGetsNoWeeklyTerm, ()) {
  // A random daily profile, the same every day: four parts of the day with their own rates.
  const auto parts = *rc::gen::container<std::vector<int>>(4, rc::gen::inRange(1, 20));
  const int weeks = *rc::gen::inRange(4, 13);
  const int step = *rc::gen::element(600, 1800);
  Uniform uniform(*rc::gen::arbitrary<std::uint64_t>());
  auto p = [&](std::int64_t tow, std::int64_t) {
    return parts[static_cast<std::size_t>((tow % 86400) / 21600)] / 20.0;
  };
  const auto series = bernoulli_series(7 * weeks, step, p, uniform);
  const auto model = fit_episode_binary(series);
  RC_LOG() << "z " << model->model().weekly().evidence << "\n";
  RC_ASSERT(!model->model().weekly().weekly);
}

TEST(Weekly, TheChoiceAndTheWeekCountsSurviveJson) {
  Uniform uniform(3);
  auto p = [](std::int64_t tow, std::int64_t) { return testing::wednesday_closure(tow, 0.95); };
  const auto fitted = fit_episode_binary(bernoulli_series(28, 1800, p, uniform));
  ASSERT_TRUE(fitted->model().weekly().weekly);
  auto loaded = binary_model_from_json(fitted->to_json());
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  const Time wednesday_15 = monday() + hours(24 * 30 + 15), tuesday_15 = monday() + hours(24 * 29 + 15);
  EXPECT_DOUBLE_EQ((*loaded)->probability(wednesday_15), fitted->probability(wednesday_15));
  EXPECT_LT(fitted->probability(wednesday_15), fitted->probability(tuesday_15) - 0.3);
  EXPECT_EQ((*loaded)->to_json(), fitted->to_json());
  // A file written before the weekly term (no week counts, no choice) loads as time of day only.
  Json old = fitted->to_json();
  old["edge"].erase("weekly");
  old["edge"]["stats"].erase("week_successes");
  old["edge"]["stats"].erase("week_attempts");
  old["priors"].erase("weekly");
  auto legacy = binary_model_from_json(old);
  ASSERT_TRUE(legacy.ok()) << legacy.error().message;
  EXPECT_GT((*legacy)->probability(wednesday_15), fitted->probability(wednesday_15) + 0.3);
  // A weekly choice without its week counts is an error.
  Json broken = fitted->to_json();
  broken["edge"]["stats"].erase("week_attempts");
  broken["edge"]["stats"].erase("week_successes");
  EXPECT_FALSE(binary_model_from_json(broken).ok());
}

TEST(Weekly, AConstantSeriesGetsNoWeeklyTerm) {
  // Always true: the week bins agree with the day bins exactly, so there is nothing to choose.
  auto p = [](std::int64_t, std::int64_t) { return 1.0; };
  Uniform uniform(1);
  const auto model = fit_episode_binary(bernoulli_series(28, 600, p, uniform));
  EXPECT_FALSE(model->model().weekly().weekly);
  EXPECT_EQ(model->model().weekly().scored, 0);
}

RC_GTEST_PROP(Weekly, FittingIsDeterministic, ()) {
  const auto levels = *gen_week_levels();
  Uniform uniform(*rc::gen::arbitrary<std::uint64_t>());
  auto p = [&](std::int64_t tow, std::int64_t) { return levels[static_cast<std::size_t>(tow / 86400)]; };
  const auto series = bernoulli_series(*rc::gen::inRange(7, 40), 3600, p, uniform);
  for (auto w : {WeeklyTerm::kAuto, WeeklyTerm::kOn}) {
    RC_ASSERT(fit_episode_binary(series, with_weekly(w))->to_json() ==
              fit_episode_binary(series, with_weekly(w))->to_json());
  }
}

// The definition of q(t), slowly: the past first attempts are put in the bins by explicit bin
// numbers (no running counts), each histogram's day estimate and week-corrected estimate averaged.
std::pair<double, double> reference_q(const std::vector<SlotAttempt>& past, int week_slot, double pooled,
                                      const EpisodeOptions& o) {
  double s_all = 0;
  for (const auto& a : past) s_all += a.success ? 1 : 0;
  const double edge = (s_all + o.edge_prior * pooled) / (static_cast<double>(past.size()) + o.edge_prior);
  double q_day = 0, q_week = 0;
  int count = 0;
  for (int bins : o.day_resolutions) {
    if (bins < 1 || 24 % bins != 0) continue;
    const int width = kDaySlots / bins;
    for (int shift = 0; shift < (bins == 1 ? 1 : 4); ++shift) {
      const int offset = shift * width / 4;
      auto day_bin = [&](int slot) { return (((slot % kDaySlots) - offset + kDaySlots) % kDaySlots) / width; };
      auto week_bin = [&](int slot) { return ((slot - offset + kWeekSlots) % kWeekSlots) / width; };
      double s = 0, n = 0, sw = 0, nw = 0;
      for (const auto& a : past) {
        if (day_bin(a.week_slot) == day_bin(week_slot)) {
          n += 1;
          s += a.success ? 1 : 0;
        }
        if (week_bin(a.week_slot) == week_bin(week_slot)) {
          nw += 1;
          sw += a.success ? 1 : 0;
        }
      }
      const double qd = (s + o.bin_prior * edge) / (n + o.bin_prior);
      q_day += qd;
      q_week += nw > 0 ? std::clamp(qd + nw / (nw + o.weekly_prior) * (sw / nw - s / n), 0.0, 1.0) : qd;
      ++count;
    }
  }
  if (count == 0) return {edge, edge};
  return {q_day / count, q_week / count};
}

// The choice, slowly: each first attempt predicted from all attempts of earlier days.
WeeklyChoice reference_choice(const std::vector<SlotAttempt>& firsts, double pooled, const EpisodeOptions& o) {
  double sum_d = 0, sum_dd = 0, day_loss = 0, week_loss = 0;
  int scored = 0;
  std::map<std::int64_t, double> by_week;  // week number since the first day -> Σd
  for (std::size_t i = 0; i < firsts.size(); ++i) {
    const SlotAttempt& f = firsts[i];
    std::vector<SlotAttempt> past;
    for (std::size_t j = 0; j < i; ++j) {
      if (firsts[j].day < f.day) past.push_back(firsts[j]);
    }
    const auto [q_day, q_week] = reference_q(past, f.week_slot, pooled, o);
    const double y = f.success ? 1 : 0;
    const double d = (q_week - y) * (q_week - y) - (q_day - y) * (q_day - y);
    day_loss += (q_day - y) * (q_day - y);
    week_loss += (q_week - y) * (q_week - y);
    sum_d += d;
    sum_dd += d * d;
    by_week[(f.day - firsts.front().day) / 7] += d;
    scored += d != 0 ? 1 : 0;
  }
  WeeklyChoice out;
  out.scored = scored;
  for (const auto& [week, sum] : by_week) out.weeks_won += week > 0 && sum < 0 ? 1 : 0;
  out.evidence = sum_dd > 0 ? -sum_d / std::sqrt(sum_dd) : 0;
  out.weekly = out.evidence >= o.weekly_evidence && out.weeks_won >= 2;
  out.day_brier = firsts.empty() ? 0 : day_loss / static_cast<double>(firsts.size());
  out.week_brier = firsts.empty() ? 0 : week_loss / static_cast<double>(firsts.size());
  return out;
}

RC_GTEST_PROP(Weekly, ChoiceMatchesTheSlowReference, ()) {
  // Up to 60 first attempts over up to 5 weeks, in time order, each with its local day.
  const auto raw = *rc::gen::container<std::vector<std::tuple<int, bool>>>(
      rc::gen::tuple(rc::gen::inRange(0, 5 * kWeekSlots), rc::gen::arbitrary<bool>()));
  std::vector<std::tuple<int, bool>> sorted(
      raw.begin(), raw.begin() + static_cast<std::ptrdiff_t>(std::min<std::size_t>(raw.size(), 60)));
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return std::get<0>(a) < std::get<0>(b); });
  std::vector<SlotAttempt> firsts;
  for (auto [slot, ok] : sorted) firsts.push_back({slot / kDaySlots, slot % kWeekSlots, ok});
  EpisodeOptions o;
  o.day_resolutions =
      *rc::gen::element(std::vector<int>{1, 2, 3, 4, 6, 8, 12}, std::vector<int>{3, 24}, std::vector<int>{5, 6});
  const double pooled = *rc::gen::inRange(0, 101) / 100.0;
  const auto fast = choose_weekly(firsts, pooled, o);
  const auto slow = reference_choice(firsts, pooled, o);
  RC_ASSERT(fast.scored == slow.scored);
  RC_ASSERT(fast.weeks_won == slow.weeks_won);
  RC_ASSERT(std::abs(fast.evidence - slow.evidence) < 1e-9);
  RC_ASSERT(fast.weekly == slow.weekly);
  RC_ASSERT(std::abs(fast.day_brier - slow.day_brier) < 1e-12);
  RC_ASSERT(std::abs(fast.week_brier - slow.week_brier) < 1e-12);
}

RC_GTEST_PROP(Weekly, FirstAttemptProbabilityMatchesTheSlowReference, ()) {
  // Samples an hour or more apart (so every one starts an episode), the weekly term forced on.
  const auto gaps = *rc::gen::container<std::vector<std::tuple<int, bool>>>(
      rc::gen::tuple(rc::gen::inRange(3600, 4 * 86400), rc::gen::arbitrary<bool>()));
  std::vector<BinarySample> samples;
  Time t = monday();
  for (auto [gap, ok] : gaps) {
    t = t + seconds(gap);
    samples.push_back({t, ok});
  }
  const auto o = with_weekly(WeeklyTerm::kOn);
  const auto model = fit_episode_binary(samples, o);
  const EpisodeEdgeModel& m = model->model();
  const Time at = monday() + seconds(*rc::gen::inRange(0, 7 * 86400));
  // The reference: every sample is a past first attempt of the same (single-edge) fit.
  std::vector<SlotAttempt> past;
  for (const auto& s : samples) past.push_back(m.priors()->slot_attempt(s.time, s.value));
  const auto [q_day, q_week] = reference_q(past, m.priors()->week_slot(at), m.priors()->first_success, o);
  RC_ASSERT(std::abs(m.first_attempt_probability(at, m.stats()) - q_week) < 1e-9);
  const auto daily = fit_episode_binary(samples, with_weekly(WeeklyTerm::kOff));
  RC_ASSERT(std::abs(daily->model().first_attempt_probability(at, daily->model().stats()) - q_day) < 1e-9);
}

// The bin counts choose_weekly keeps against the sums over the slot counts they replace: the same
// estimates exactly, for every histogram, with and without the weekly term.
RC_GTEST_PROP(Weekly, BinCountsEqualTheSlotSums, ()) {
  EpisodeOptions o;
  o.day_resolutions =
      *rc::gen::element(std::vector<int>{1, 2, 3, 4, 6, 8, 12}, std::vector<int>{3, 24}, std::vector<int>{5, 6});
  const auto attempts = *rc::gen::container<std::vector<std::tuple<int, bool>>>(
      rc::gen::tuple(rc::gen::inRange(0, kWeekSlots), rc::gen::arbitrary<bool>()));
  std::vector<double> day_s(kDaySlots, 0.0), day_a(kDaySlots, 0.0), week_s(kWeekSlots, 0.0), week_a(kWeekSlots, 0.0);
  BinCounts bins(o.day_resolutions);
  for (auto [slot, ok] : attempts) {
    bins.add(slot, ok);
    day_a[static_cast<std::size_t>(slot % kDaySlots)] += 1;
    week_a[static_cast<std::size_t>(slot)] += 1;
    day_s[static_cast<std::size_t>(slot % kDaySlots)] += ok ? 1 : 0;
    week_s[static_cast<std::size_t>(slot)] += ok ? 1 : 0;
  }
  const SlotCounts slots{day_s.data(), day_a.data(), week_s.data(), week_a.data()};
  const double edge = *rc::gen::inRange(0, 101) / 100.0;
  const bool weekly = *rc::gen::arbitrary<bool>();
  for (int slot = 0; slot < kWeekSlots; ++slot) {
    std::vector<std::pair<double, double>> summed, binned;
    for_each_bin_estimate(slot, slots, edge, o, weekly, [&](double d, double w) { summed.emplace_back(d, w); });
    bins.for_each_bin_estimate(slot, edge, o, weekly, [&](double d, double w) { binned.emplace_back(d, w); });
    RC_ASSERT(binned == summed);
  }
}

}  // namespace
}  // namespace rondo::learn
