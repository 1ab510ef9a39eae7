// The offline duration tables computed when first read (OfflineDurations) against the
// straightforward computation they defer (offline_duration_tables on the same attempts and priors):
// equal bit for bit, whichever edge is read first, through quantile_seconds and the model's JSON,
// and when several threads read them at once.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <random>
#include <thread>

#include "offline_durations.h"
#include "rondo/learn/edge_models.h"
#include "rondo/learn/episode_model.h"
#include "series.h"

namespace rondo::learn {
namespace {

using testing::monday;

// `edges` random edges over `days`: attempts at random times, some failing with quick retries,
// random durations; in start order (each edge's attempts do not overlap).
std::vector<std::vector<Attempt>> random_edges(int edges, int days, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::vector<Attempt>> out(static_cast<std::size_t>(edges));
  for (auto& attempts : out) {
    const int n = static_cast<int>(u(rng) * 40.0 * days);
    Time t = monday() + seconds(static_cast<int>(u(rng) * 3600));
    for (int i = 0; i < n; ++i) {
      t = t + seconds(static_cast<int>(u(rng) * 86400.0 * days / std::max(n, 1)));
      const double secs = u(rng) < 0.3 ? 5.0 + std::floor(u(rng) * 3) : 5.0 + 60.0 * u(rng);
      const bool ok = u(rng) < 0.8;
      attempts.push_back({t, t + from_seconds(secs), secs, ok});
      t = t + from_seconds(secs) + seconds(ok || u(rng) < 0.5 ? 120 : 2);  // a failure is often retried at once
    }
  }
  return out;
}

EpisodeOptions random_options() {
  EpisodeOptions o;
  o.duration_mixture = *rc::gen::arbitrary<bool>();
  if (*rc::gen::arbitrary<bool>()) o.zone = TimeZone::named("Europe/London").value();
  if (*rc::gen::arbitrary<bool>()) o.duration_half_life = Duration{0};
  return o;
}

RC_GTEST_PROP(OfflineDurations, EqualTheEagerTablesWhicheverEdgeIsReadFirst, ()) {
  const EpisodeOptions options = random_options();
  const int n = *rc::gen::inRange(1, 5);
  const auto edges = random_edges(n, *rc::gen::inRange(1, 10), *rc::gen::arbitrary<std::uint32_t>());
  const EpisodeFit fit = fit_episode_models(edges, options);
  const auto eager = offline_duration_tables(edges, *fit.priors);
  const auto first = static_cast<std::size_t>(*rc::gen::inRange(0, n));
  // Through the offline quantiles: the first read computes every edge's tables.
  const Time t = monday() + minutes(15 * *rc::gen::inRange(0, 7 * kDaySlots)) + seconds(*rc::gen::inRange(0, 900));
  const double q = *rc::gen::element(0.1, 0.5, 0.9);
  RC_ASSERT(fit.edges[first]->quantile_seconds(t, q) ==
            eager[first][static_cast<std::size_t>(fit.priors->day_slot(t))].at(q));
  // Through the saved tables, every edge.
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const Json offline = fit.edges[e]->to_json()["durations"]["offline"];
    RC_ASSERT(offline.size() == eager[e].size());
    for (std::size_t s = 0; s < eager[e].size(); ++s) RC_ASSERT(offline[s] == eager[e][s].to_json());
  }
}

TEST(OfflineDurations, AreComputedOnlyWhenRead) {
  const auto edges = random_edges(3, 4, 7);
  const EpisodeFit fit = fit_episode_models(edges, {});
  const auto eager = offline_duration_tables(edges, *fit.priors);
  const OfflineDurations lazy(edges, fit.priors);
  EXPECT_FALSE(lazy.computed());
  EXPECT_EQ(lazy.of_edge(2)[40].values(), eager[2][40].values());
  EXPECT_TRUE(lazy.computed());
  const OfflineDurations given(std::vector<std::vector<QuantileTable>>{eager[1]});
  EXPECT_TRUE(given.computed());
  EXPECT_EQ(given.of_edge(0)[95].values(), eager[1][95].values());
}

// What a refit gives it: attempts made from traversals (whole milliseconds, seconds = their
// to_seconds). They are kept in 8 bytes each, not an Attempt's 32, and give the same tables.
std::vector<std::vector<Attempt>> traversal_attempts(std::vector<std::vector<Attempt>> edges) {
  for (auto& attempts : edges)
    for (Attempt& a : attempts) a.seconds = to_seconds(a.end - a.start);
  return edges;
}

std::size_t attempt_count(const std::vector<std::vector<Attempt>>& edges) {
  std::size_t n = 0;
  for (const auto& e : edges) n += e.size();
  return n;
}

RC_GTEST_PROP(OfflineDurations, KeepTraversalAttemptsCompactlyAndGiveTheSameTables, ()) {
  const EpisodeOptions options = random_options();
  const int n = *rc::gen::inRange(1, 5);
  const auto edges =
      traversal_attempts(random_edges(n, *rc::gen::inRange(1, 10), *rc::gen::arbitrary<std::uint32_t>()));
  const EpisodeFit fit = fit_episode_models(edges, options);
  const auto eager = offline_duration_tables(edges, *fit.priors);
  const OfflineDurations lazy(edges, fit.priors);
  RC_ASSERT(lazy.input_bytes() <= 8 * attempt_count(edges) + 32 * edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e)
    for (std::size_t k = 0; k < eager[e].size(); ++k) RC_ASSERT(lazy.of_edge(e)[k].values() == eager[e][k].values());
  RC_ASSERT(lazy.input_bytes() == 0u);
}

TEST(OfflineDurations, KeepOtherAttemptsAsTheyAre) {
  // A duration in seconds that is not whole milliseconds, a failure at once (-0.0 s), a start
  // more than 24 days after the previous one: each is kept as given, and the tables are the same.
  for (int kind = 0; kind < 3; ++kind) {
    auto edges = traversal_attempts(random_edges(2, 3, 5));
    Attempt& a = edges[1][3];
    if (kind == 0) a.seconds += 0.0001;
    if (kind == 1) a = {a.start, a.start, -0.0, false};
    if (kind == 2)
      edges[0].push_back(
          {edges[0].back().start + hours(24 * 25), edges[0].back().start + hours(24 * 25) + seconds(9), 9.0, true});
    const EpisodeFit fit = fit_episode_models(edges, {});
    const auto eager = offline_duration_tables(edges, *fit.priors);
    const OfflineDurations lazy(edges, fit.priors);
    EXPECT_GE(lazy.input_bytes(), 32 * attempt_count(edges)) << kind;
    for (std::size_t e = 0; e < edges.size(); ++e)
      for (std::size_t k = 0; k < eager[e].size(); ++k)
        EXPECT_EQ(lazy.of_edge(e)[k].values(), eager[e][k].values()) << kind << " " << e << " " << k;
  }
}

TEST(OfflineDurations, ALoadedModelAnswersAsTheFittedOne) {
  std::vector<Traversal> log;
  const auto edges = random_edges(1, 5, 11);
  for (const Attempt& a : edges[0])
    log.push_back({.edge_id = "A_B", .start = a.start, .duration = a.end - a.start, .success = a.success});
  const std::vector<EdgeSpec> specs{{"A_B", 20.0}};
  const auto fitted = EdgeModels::fit(specs, log).value();
  const auto loaded = EdgeModels::from_json(fitted->to_json()).value();
  for (int k = 0; k < kDaySlots; ++k) {
    const Time t = monday() + hours(24 * 9) + minutes(15 * k);
    EXPECT_EQ(loaded->quantile_seconds(0, t, 0.9), fitted->quantile_seconds(0, t, 0.9)) << k;
  }
}

TEST(OfflineDurations, ThreadsReadingAtOnceSeeTheSameTables) {
  const auto edges = random_edges(4, 6, 3);
  const EpisodeFit fit = fit_episode_models(edges, {});
  const auto eager = offline_duration_tables(edges, *fit.priors);
  std::vector<std::vector<double>> seen(4);
  std::vector<std::thread> readers;
  for (std::size_t e = 0; e < 4; ++e)
    readers.emplace_back([&, e] {
      for (int k = 0; k < kDaySlots; ++k)
        seen[e].push_back(fit.edges[e]->quantile_seconds(monday() + minutes(15 * k), 0.5));
    });
  for (auto& r : readers) r.join();
  for (std::size_t e = 0; e < 4; ++e)
    for (std::size_t k = 0; k < seen[e].size(); ++k) EXPECT_EQ(seen[e][k], eager[e][k].at(0.5)) << e << " " << k;
}

}  // namespace
}  // namespace rondo::learn
