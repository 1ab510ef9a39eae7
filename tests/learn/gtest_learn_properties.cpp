// Invariants of every model, checked on generated series (RapidCheck).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>

#include "rondo/learn/edge_models.h"
#include "rondo/learn/episode_model.h"
#include "rondo/learn/fremen.h"
#include "rondo/learn/static_model.h"
#include "series.h"

namespace rondo::learn {
namespace {

using testing::monday;

// A time-ordered series of attempts: gaps from 1 s to 3 days, durations 0..600 s.
rc::Gen<std::vector<Attempt>> gen_attempts() {
  return rc::gen::map(rc::gen::container<std::vector<std::tuple<int, int, bool>>>(rc::gen::tuple(
                          rc::gen::inRange(1, 3 * 86400), rc::gen::inRange(0, 600000), rc::gen::arbitrary<bool>())),
                      [](const std::vector<std::tuple<int, int, bool>>& raw) {
                        std::vector<Attempt> out;
                        Time t = monday();
                        for (auto [gap, ms, ok] : raw) {
                          t = t + seconds(gap);
                          const double secs = ms / 1000.0;
                          out.push_back({t, t + from_seconds(secs), secs, ok});
                          t = t + from_seconds(secs);
                        }
                        return out;
                      });
}

std::vector<BinarySample> flags_of(const std::vector<Attempt>& attempts) {
  std::vector<BinarySample> out;
  for (const auto& a : attempts) out.push_back({a.start, a.success});
  return out;
}

std::vector<DurationSample> durations_of(const std::vector<Attempt>& attempts) {
  std::vector<DurationSample> out;
  for (const auto& a : attempts) out.push_back({a.start, a.seconds});
  return out;
}

Time gen_time() {
  return monday() + seconds(*rc::gen::inRange(0, 60 * 86400));
}

RC_GTEST_PROP(LearnProperties, ProbabilitiesStayInZeroOne, ()) {
  const auto attempts = *gen_attempts();
  const int order = *rc::gen::inRange(0, 6);
  const auto flags = flags_of(attempts);
  auto fremen = fit_fremen_binary(flags, {.order = order});
  auto fixed = fit_static_binary(flags);
  auto episode = fit_episode_models({attempts});
  EpisodePredictor live(episode.edges[0]);
  for (int i = 0; i < 20; ++i) {
    const Time t = gen_time();
    for (double p :
         {fremen->probability(t), fixed->probability(t), episode.edges[0]->probability(t), live.probability(t)}) {
      RC_ASSERT(p >= 0.0);
      RC_ASSERT(p <= 1.0);
    }
    live.observe({t, t + seconds(5), 5.0, *rc::gen::arbitrary<bool>()});
  }
}

RC_GTEST_PROP(LearnProperties, QuantilesAreMonotone, ()) {
  const auto attempts = *gen_attempts();
  auto fremen = fit_fremen_duration(durations_of(attempts), {.order = *rc::gen::inRange(0, 4)});
  auto fixed = fit_static_duration(durations_of(attempts));
  auto episode = fit_episode_models({attempts});
  EpisodePredictor live(episode.edges[0]);
  if (!attempts.empty()) live.observe(attempts.back());
  const Time t = attempts.empty() ? gen_time() : attempts.back().end + seconds(*rc::gen::inRange(0, 120));
  auto check = [](auto&& quantile) {
    double previous = 0;
    for (double q = 0.01; q < 1.0; q += 0.01) {
      const double v = quantile(q);
      RC_ASSERT(v >= 0.0);
      RC_ASSERT(v >= previous - 1e-9);
      previous = v;
    }
  };
  check([&](double q) { return fremen->quantile_seconds(t, q); });
  check([&](double q) { return fixed->quantile_seconds(t, q); });
  check([&](double q) { return episode.edges[0]->quantile_seconds(t, q); });
  check([&](double q) { return live.quantile_seconds(t, q); });
}

RC_GTEST_PROP(LearnProperties, AConstantSeriesPredictsThatConstant, ()) {
  const auto raw = *rc::gen::nonEmpty(gen_attempts());
  const bool value = *rc::gen::arbitrary<bool>();
  const double secs = *rc::gen::inRange(1, 500);
  std::vector<Attempt> attempts;
  for (auto a : raw) {
    a.success = value;
    a.seconds = secs;
    a.end = a.start + from_seconds(secs);
    attempts.push_back(a);
  }
  const Time t = gen_time();
  const double expected = value ? 1.0 : 0.0;
  RC_ASSERT(fit_static_binary(flags_of(attempts))->probability(t) == expected);
  // FreMEn clamps its probabilities to [0.01, 0.99].
  RC_ASSERT(std::abs(fit_fremen_binary(flags_of(attempts), {.order = 2})->probability(t) -
                     std::clamp(expected, 0.01, 0.99)) < 1e-6);
  RC_ASSERT(std::abs(fit_fremen_duration(durations_of(attempts), {.order = 2})->expected_seconds(t) - secs) <
            1e-3 * secs);
  auto episode = fit_episode_models({attempts});
  const auto& model = *episode.edges[0];
  RC_ASSERT(std::abs(model.probability(t) - expected) < 1e-12);
  RC_ASSERT(std::abs(model.expected_seconds(t) - secs) < 1e-9 * secs);
  RC_ASSERT(std::abs(model.quantile_seconds(t, 0.9) - secs) < 1e-9 * secs);
  EpisodePredictor live(episode.edges[0]);
  const Time later = attempts.back().end + seconds(*rc::gen::inRange(0, 7200));
  RC_ASSERT(std::abs(live.probability(later) - expected) < 1e-12);
  RC_ASSERT(std::abs(live.quantile_seconds(later, 0.5) - secs) < 1e-9 * secs);
}

RC_GTEST_PROP(LearnProperties, FittingIsDeterministic, ()) {
  const auto attempts = *gen_attempts();
  RC_ASSERT(fit_fremen_binary(flags_of(attempts), {.order = 3})->to_json() ==
            fit_fremen_binary(flags_of(attempts), {.order = 3})->to_json());
  RC_ASSERT(fit_episode_binary(flags_of(attempts))->to_json() == fit_episode_binary(flags_of(attempts))->to_json());
  std::vector<Traversal> log;
  for (const auto& a : attempts) log.push_back({"A_B", "A", "B", a.start, from_seconds(a.seconds), a.success, ""});
  const std::vector<EdgeSpec> edges = {{"A_B", 10}, {"B_A", 0}};
  RC_ASSERT((*EdgeModels::fit(edges, log))->to_json() == (*EdgeModels::fit(edges, log))->to_json());
}

// The slow obvious form of QuantileTable::from_weighted_samples: every sample's share centre, and
// for each level a linear search for the centres around it.
std::vector<double> reference_weighted_quantiles(std::vector<QuantileTable::WeightedValue> samples) {
  std::erase_if(samples, [](const auto& s) { return !(s.weight > 0); });
  std::vector<double> out;
  if (samples.empty()) return std::vector<double>(QuantileTable::kKnots, 0.0);
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.value < b.value; });
  std::vector<QuantileTable::WeightedValue> merged;  // one point mass per distinct value
  for (const auto& s : samples) {
    if (!merged.empty() && merged.back().value == s.value) {
      merged.back().weight += s.weight;
    } else {
      merged.push_back(s);
    }
  }
  samples = merged;
  double total = 0;
  for (const auto& s : samples) total += s.weight;
  std::vector<double> centre;
  double before = 0;
  for (const auto& s : samples) {
    centre.push_back((before + s.weight / 2) / total);
    before += s.weight;
  }
  for (int k = 0; k < QuantileTable::kKnots; ++k) {
    const double p = QuantileTable::level(k);
    double v = samples.back().value;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (centre[i] < p) continue;
      if (i == 0 || centre[i] == centre[i - 1]) {
        v = samples[i].value;
      } else {
        const double f = (p - centre[i - 1]) / (centre[i] - centre[i - 1]);
        v = samples[i - 1].value + f * (samples[i].value - samples[i - 1].value);
      }
      break;
    }
    out.push_back(std::max(0.0, v));
  }
  return out;
}

RC_GTEST_PROP(LearnProperties, WeightedQuantilesMatchTheReference, ()) {
  const auto raw = *rc::gen::container<std::vector<std::pair<int, int>>>(
      rc::gen::pair(rc::gen::inRange(-50, 5000), rc::gen::inRange(0, 100)));
  std::vector<QuantileTable::WeightedValue> samples;
  for (auto [value, weight] : raw) samples.push_back({value / 10.0, weight / 7.0});
  const auto fast = QuantileTable::from_weighted_samples(samples).values();
  const auto slow = reference_weighted_quantiles(samples);
  // Samples already in value order take the path that does not sort.
  auto in_order = samples;
  std::stable_sort(in_order.begin(), in_order.end(), [](const auto& x, const auto& y) { return x.value < y.value; });
  const auto presorted = QuantileTable::from_weighted_samples(in_order).values();
  for (std::size_t k = 0; k < fast.size(); ++k) {
    RC_ASSERT(std::abs(fast[k] - slow[k]) <= 1e-9 * (1 + std::abs(slow[k])));
    RC_ASSERT(std::abs(presorted[k] - slow[k]) <= 1e-9 * (1 + std::abs(slow[k])));
    if (k > 0) RC_ASSERT(fast[k] >= fast[k - 1]);
  }
  // Blends and averages of monotone tables stay monotone and between their inputs.
  const auto a = QuantileTable::from_weighted_samples(samples);
  const auto b = QuantileTable::from_samples({1.0, 2.0, 400.0});
  const double w = *rc::gen::inRange(0, 100) / 100.0;
  const auto mixed = QuantileTable::blend(a, b, w);
  const std::vector<QuantileTable> both = {a, b};
  const auto mean = QuantileTable::average(both);
  for (std::size_t k = 0; k < fast.size(); ++k) {
    const double lo = std::min(a.values()[k], b.values()[k]), hi = std::max(a.values()[k], b.values()[k]);
    RC_ASSERT(mixed.values()[k] >= lo - 1e-9 && mixed.values()[k] <= hi + 1e-9);
    RC_ASSERT(mean.values()[k] >= lo - 1e-9 && mean.values()[k] <= hi + 1e-9);
    if (k > 0) RC_ASSERT(mixed.values()[k] >= mixed.values()[k - 1] && mean.values()[k] >= mean.values()[k - 1]);
  }
}

// The CDF a table describes (QuantileTable::mixture's contract), evaluated directly: 0 below the
// first knot, the last knot's level plus its 0.02 tail at and above it, linear in between.
double reference_cdf(const QuantileTable& t, double x) {
  const auto& v = t.values();
  if (x < v.front()) return 0.0;
  std::size_t k = 0;
  while (k + 1 < v.size() && v[k + 1] <= x) ++k;
  if (k + 1 == v.size()) return 1.0;
  return QuantileTable::level(static_cast<int>(k)) + 0.02 * (x - v[k]) / (v[k + 1] - v[k]);
}

// The mixture's quantiles by bisection on the weighted mean of the CDFs.
std::vector<double> reference_mixture(const std::vector<QuantileTable>& tables, const std::vector<double>& weights) {
  double total = 0, lo = 1e300, hi = -1e300;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    total += weights[i];
    lo = std::min(lo, tables[i].values().front());
    hi = std::max(hi, tables[i].values().back());
  }
  auto cdf = [&](double x) {
    double f = 0;
    for (std::size_t i = 0; i < tables.size(); ++i) f += weights[i] / total * reference_cdf(tables[i], x);
    return f;
  };
  std::vector<double> out;
  for (int k = 0; k < QuantileTable::kKnots; ++k) {
    double a = lo, b = hi;  // invariant: cdf(b) >= level
    for (int it = 0; it < 60; ++it) {
      const double m = (a + b) / 2;
      (cdf(m) >= QuantileTable::level(k) - 1e-12 ? b : a) = m;
    }
    out.push_back(cdf(lo) >= QuantileTable::level(k) - 1e-12 ? lo : b);
  }
  return out;
}

RC_GTEST_PROP(LearnProperties, MixturesMatchTheReference, ()) {
  const auto n = *rc::gen::inRange<std::size_t>(1, 5);
  std::vector<QuantileTable> tables;
  std::vector<double> weights;
  for (std::size_t i = 0; i < n; ++i) {
    // Few distinct values: atoms (runs of equal knots) are common.
    const auto values = *rc::gen::nonEmpty(rc::gen::container<std::vector<int>>(rc::gen::inRange(0, 20)));
    std::vector<double> v;
    for (int x : values) v.push_back(5.0 * x);
    tables.push_back(QuantileTable::from_samples(v));
    weights.push_back(*rc::gen::inRange(1, 100) / 10.0);
  }
  const auto fast = QuantileTable::mixture(tables, weights).values();
  const auto slow = reference_mixture(tables, weights);
  for (std::size_t k = 0; k < fast.size(); ++k) {
    RC_ASSERT(std::abs(fast[k] - slow[k]) <= 1e-6 * (1.0 + std::abs(slow[k])));
    if (k > 0) RC_ASSERT(fast[k] >= fast[k - 1]);
    double lo = 1e300, hi = -1e300;
    for (const auto& t : tables) {
      lo = std::min(lo, t.values()[k]);
      hi = std::max(hi, t.values()[k]);
    }
    RC_ASSERT(fast[k] >= lo - 1e-9 && fast[k] <= hi + 1e-9);
  }
  // A mixture of copies of one table is that table.
  const std::vector<QuantileTable> copies(3, tables[0]);
  const auto same = QuantileTable::mixture(copies, std::vector<double>{1.0, 2.0, 3.0}).values();
  for (std::size_t k = 0; k < same.size(); ++k) RC_ASSERT(std::abs(same[k] - tables[0].values()[k]) <= 1e-9);
}

// The mixer over a sequence of member sets, each changing some members of the one before (as the
// slots of a day do), gives exactly QuantileTable::mixture of the same members in rank order.
RC_GTEST_PROP(LearnProperties, TheMixerEqualsMixtureBitForBit, ()) {
  const auto pool_size = *rc::gen::inRange<std::size_t>(1, 8);
  std::vector<QuantileTable> pool;
  for (std::size_t i = 0; i < pool_size; ++i) {
    const auto values = *rc::gen::nonEmpty(rc::gen::container<std::vector<int>>(rc::gen::inRange(0, 20)));
    std::vector<double> v;
    for (int x : values) v.push_back(5.0 * x);  // few distinct values: ties and atoms are common
    pool.push_back(QuantileTable::from_samples(v));
  }
  const auto ranks = *rc::gen::inRange<std::uint32_t>(1, 6);
  const auto calls = *rc::gen::inRange(1, 12);
  QuantileMixer mixer;
  for (int c = 0; c < calls; ++c) {
    std::vector<QuantileMixer::Member> members;
    std::vector<const QuantileTable*> tables;
    std::vector<double> weights;
    for (std::uint32_t r = 0; r < ranks; ++r) {
      if (!*rc::gen::inRange(0, 4)) continue;  // a quarter of the ranks are empty
      const auto& t = pool[*rc::gen::inRange<std::size_t>(0, pool_size)];
      const double w = *rc::gen::inRange(0, 50) / 10.0;  // zero weights are left out by both
      members.push_back({.table = &t, .weight = w, .rank = r});
      tables.push_back(&t);
      weights.push_back(w);
    }
    const auto fast = mixer.mix(members).values();
    const auto plain = QuantileTable::mixture(std::span<const QuantileTable* const>(tables), weights).values();
    RC_ASSERT(fast == plain);
  }
}

TEST(QuantileTable, AMixtureKeepsBothModesWhereABlendAveragesThem) {
  const std::vector<QuantileTable> modes = {QuantileTable::from_samples({10.0}), QuantileTable::from_samples({100.0})};
  const auto mixed = QuantileTable::mixture(modes, std::vector<double>{0.7, 0.3});
  EXPECT_DOUBLE_EQ(mixed.at(0.02), 10.0);
  EXPECT_DOUBLE_EQ(mixed.at(0.5), 10.0);
  EXPECT_DOUBLE_EQ(mixed.at(0.68), 10.0);
  EXPECT_DOUBLE_EQ(mixed.at(0.72), 100.0);
  EXPECT_DOUBLE_EQ(mixed.at(0.9), 100.0);
  EXPECT_DOUBLE_EQ(QuantileTable::blend(modes[0], modes[1], 0.7).at(0.9), 37.0);
  // No weight, no table: all zeros.
  EXPECT_DOUBLE_EQ(QuantileTable::mixture(modes, std::vector<double>{0.0, -1.0}).at(0.9), 0.0);
}

}  // namespace
}  // namespace rondo::learn
