// LearnedEdgeModels: map edges matched to a learn::EdgeModels snapshot by id, the distance prior
// for edges it does not know, and set() moving version() on so that TravelPlanner drops its caches.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>

#include "rondo/learn/edge_models.h"
#include "rondo/map/map_geometry.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/travel_planner.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

using testing::small_map;

const Time kStart = Time{} + hours(24 * 16000);

// `n` attempts on `edge`, one every 10 minutes: every `fail_every`-th fails (0: none fail).
std::vector<Traversal> attempts(const std::string& edge, int n, double seconds, int fail_every) {
  std::vector<Traversal> out;
  const auto cut = edge.find('_');
  for (int i = 0; i < n; ++i) {
    out.push_back({.edge_id = edge,
                   .from = edge.substr(0, cut),
                   .to = edge.substr(cut + 1),
                   .start = kStart + minutes(10 * i),
                   .duration = from_seconds(seconds),
                   .success = fail_every == 0 || (i + 1) % fail_every != 0});
  }
  return out;
}

std::shared_ptr<const learn::EdgeModels> fit(const std::vector<learn::EdgeSpec>& specs,
                                             const std::vector<Traversal>& log) {
  return learn::EdgeModels::fit(specs, log).value();
}

TEST(EdgeSpecs, OnePerMapEdgeWithTheDistancePrior) {
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "B>C", "C>A"});
  const auto specs = edge_specs(m);
  ASSERT_EQ(specs.size(), 3u);
  for (map::EdgeIndex e = 0; e < 3; ++e) {
    EXPECT_EQ(specs[e].id, m.edge(e).id);
    EXPECT_DOUBLE_EQ(specs[e].prior_seconds, to_seconds(map::nominal_travel_time(m, e)));
    EXPECT_GT(specs[e].prior_seconds, 0.0);
  }
}

TEST(LearnedEdgeModels, KnownEdgesAnswerFromTheModelsOthersFromThePrior) {
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "B>C", "C>A"});
  // The models know A_B (with data) and B_C (without), plus an edge the map lacks.
  std::vector<learn::EdgeSpec> specs = {{"A_B", 2.0}, {"B_C", 2.0}, {"X_Y", 5.0}};
  auto log = attempts("A_B", 60, 30.0, 3);
  auto models = fit(specs, log);
  LearnedEdgeModels view(m, models);
  EXPECT_EQ(view.known_edge_count(), 2u);
  EXPECT_EQ(view.model_index(0), *models->index_of("A_B"));
  EXPECT_EQ(view.model_index(2), LearnedEdgeModels::kUnknown);
  const DistancePrior prior(m);
  const Time t = kStart + hours(30);
  for (map::EdgeIndex e = 0; e < 2; ++e) {
    const std::size_t i = view.model_index(e);
    EXPECT_EQ(view.outcome(e, t),
              (EdgeCrossing{models->success_probability(i, t), models->expected_seconds(i, t)}));
  }
  EXPECT_EQ(view.outcome(2, t), prior.outcome(2, t));
  // The fitted edge learned its slowness and its failures: far from the prior's 2 s and p = 1.
  EXPECT_GT(view.outcome(0, t).expected_seconds, 10.0);
  EXPECT_LT(view.outcome(0, t).success_probability, 0.95);
}

TEST(LearnedEdgeModels, NullModelsMeanThePriorEverywhere) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B", "B>A"});
  LearnedEdgeModels view(m, nullptr, {.success_probability = 0.8});
  const DistancePrior prior(m, {.success_probability = 0.8});
  EXPECT_EQ(view.known_edge_count(), 0u);
  for (map::EdgeIndex e = 0; e < 2; ++e) EXPECT_EQ(view.outcome(e, kStart), prior.outcome(e, kStart));
}

TEST(LearnedEdgeModels, SetSwapsTheSnapshotAndTheOracleDropsItsCaches) {
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "B>C", "A>C"});
  const auto specs = edge_specs(m);
  auto fast = fit(specs, attempts("A_C", 40, 3.0, 0));
  auto view = std::make_shared<LearnedEdgeModels>(m, fast);
  TravelPlanner oracle(m, view);
  const Time t = kStart + hours(50);
  const double before = oracle.expected_seconds(0, 2, t);
  EXPECT_NEAR(before, 3.0, 0.5);  // straight A -> C, learned to take 3 s
  EXPECT_EQ(oracle.policy(2, t).next_edge(0), m.find_edge("A_C"));

  // The nightly refit: A -> C turned slow and unreliable.
  std::vector<Traversal> log = attempts("A_C", 40, 300.0, 2);
  const std::uint64_t v = view->version();
  view->set(fit(specs, log));
  EXPECT_NE(view->version(), v);
  const double after = oracle.expected_seconds(0, 2, t);
  EXPECT_GT(after, before * 10);
  EXPECT_EQ(oracle.cached_policy_count(), 1u);  // the old policy is gone, the new one cached
  view->set(nullptr);
  EXPECT_DOUBLE_EQ(oracle.expected_seconds(0, 2, t), ExactSolver{}
                                                         .solve(Mdp::build(m, DistancePrior(m), t), 2)
                                                         .value()
                                                         .policy.expected_seconds(0));
}

// Four weeks of A_B tried every 10 minutes, closed daily 10:00-13:00 (each attempt and its retry,
// started as it ends, as the executor retries, fail): the log teaches the online model that a
// failure is followed by failures.
std::vector<Traversal> daily_closures() {
  std::vector<Traversal> log;
  for (int day = 0; day < 28; ++day)
    for (int slot = 0; slot < 144; ++slot) {
      const Time start = kStart + hours(24 * day) + minutes(10 * slot);
      const bool closed = slot >= 60 && slot < 78;
      log.push_back({"A_B", "A", "B", start, seconds(20), !closed, ""});
      if (closed) log.push_back({"A_B", "A", "B", start + seconds(20), seconds(20), false, ""});
    }
  return log;
}

TEST(LearnedEdgeModels, OnlineAFailureRaisesTheTravelTimeAtOnceAndIsForgotten) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B", "B>A"});
  const std::vector<learn::EdgeSpec> specs = {{"A_B", 20.0}, {"B_A", 20.0}};
  auto fitted = fit(specs, daily_closures());
  auto live =
      std::make_shared<LearnedEdgeModels>(m, fitted, DistancePriorOptions{}, LearnedEdgeModels::Reading::kOnline);
  TravelPlanner oracle(m, live);
  const map::EdgeIndex a_b = *m.find_edge("A_B");
  const Time t = kStart + hours(24 * 28 + 15);  // day 29, 15:00: open
  EXPECT_TRUE(live->observe(a_b, {t - minutes(10), t - minutes(10) + seconds(20), 20.0, true}));
  const double before = oracle.expected_seconds(0, 1, t);
  const std::uint64_t v = live->version();
  EXPECT_TRUE(live->observe(a_b, {t, t + seconds(20), 20.0, false}));
  EXPECT_EQ(live->version(), v + 1);
  EXPECT_EQ(live->changed_since(v), (std::vector<map::EdgeIndex>{a_b}));  // that edge only
  // Read at the slot's start, before the failure ended: as right after it (a gap of 0).
  const double at_once = oracle.expected_seconds(0, 1, t + seconds(20));
  const double later = oracle.expected_seconds(0, 1, t + hours(6));
  EXPECT_GT(at_once, 3 * before);  // the next try is expected to fail again
  EXPECT_LT(later, 1.5 * before);  // six hours later the closure is forgotten
  EXPECT_EQ(oracle.expected_seconds(1, 0, t + seconds(20)), oracle.expected_seconds(1, 0, t));  // B_A saw nothing
  // A refit starts again from the snapshot: changed_since cannot list edges across it.
  live->set(fitted);
  EXPECT_FALSE(live->changed_since(v).has_value());
}

TEST(LearnedEdgeModels, OfflineIgnoresObservations) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B", "B>A"});
  auto fitted = fit({{"A_B", 20.0}, {"B_A", 20.0}}, daily_closures());
  LearnedEdgeModels offline(m, fitted);
  const std::uint64_t v = offline.version();
  const Time t = kStart + hours(24 * 28 + 15);
  EXPECT_FALSE(offline.observe(0, {t, t + seconds(20), 20.0, false}));
  EXPECT_EQ(offline.version(), v);
  EXPECT_EQ(offline.outcome(0, t + seconds(30)), (EdgeCrossing{fitted->success_probability(0, t + seconds(30)),
                                                              fitted->expected_seconds(0, t + seconds(30))}));
}

}  // namespace
}  // namespace rondo::plan

namespace rondo::plan {
namespace {

// With laws set, an edge with its own model answers its own duration tables (successful attempts
// 30 s, failed ones 90 s here); an edge on the prior model the pooled laws scaled by its τ.
// Without laws, nothing.
TEST(LearnedEdgeModels, AttemptLawsFromTheEdgesTablesOrThePooledLaws) {
  const map::TopoMap m = testing::small_map({"A", "B", "C"}, {"A>B", "B>C"});
  std::vector<learn::EdgeSpec> specs = {{"A_B", 2.0}, {"B_C", 2.0}};
  auto log = attempts("A_B", 60, 30.0, 0);
  for (auto& t : attempts("A_B", 30, 90.0, 1)) {
    t.start += minutes(3);
    log.push_back(t);
  }
  std::sort(log.begin(), log.end(), [](const Traversal& a, const Traversal& b) { return a.start < b.start; });
  LearnedEdgeModels view(m, fit(specs, log));
  RouteLeg none{.success_probability = 0.5, .attempt_seconds = 10.0};
  view.attempt_laws(0, kStart, none);
  EXPECT_TRUE(none.success_law.empty());
  EXPECT_TRUE(none.failure_law.empty());

  view.set_attempt_laws(std::make_shared<const AttemptLaws>(
      AttemptLaws{.success = {{1.0, 1.0}}, .failure = {{0.5, 1.0}, {2.0, 1.0}}}));
  view.set(view.models());
  RouteLeg own{.success_probability = 0.5, .attempt_seconds = 10.0};
  view.attempt_laws(0, kStart + minutes(30), own);
  ASSERT_EQ(own.success_law.size(), LearnedEdgeModels::kLawPoints);
  ASSERT_EQ(own.failure_law.size(), LearnedEdgeModels::kLawPoints);
  for (const DurationPoint& d : own.success_law) EXPECT_NEAR(d.seconds, 30.0, 1e-6);
  for (const DurationPoint& d : own.failure_law) EXPECT_NEAR(d.seconds, 90.0, 1e-6);

  RouteLeg pooled{.success_probability = 0.5, .attempt_seconds = 10.0};
  view.attempt_laws(1, kStart, pooled);
  EXPECT_EQ(pooled.success_law, (std::vector<DurationPoint>{{10.0, 1.0}}));
  EXPECT_EQ(pooled.failure_law, (std::vector<DurationPoint>{{5.0, 1.0}, {20.0, 1.0}}));
}

// Stopped attempts (the share c of an edge's attempts, AttemptLaws::stopped) are a third way an
// attempt goes: success p (1 − c); of the rest, the stopped share p c / (1 − p (1 − c)) lasts the
// stopped law, whichever failure law (own tables or pooled) the edge has. Other edges keep theirs.
TEST(LearnedEdgeModels, StoppedAttemptsLowerTheSuccessAndJoinTheFailureLaw) {
  const map::TopoMap m = testing::small_map({"A", "B", "C"}, {"A>B", "B>C"});
  LearnedEdgeModels view(m, nullptr);
  AttemptLaws laws{.success = {{1.0, 1.0}}, .failure = {{0.5, 1.0}}};
  laws.stopped.resize(1);  // only edge 0 (A>B)
  laws.stopped[0] = {.share = 0.25, .law = {{200.0, 3.0}}};
  view.set_attempt_laws(std::make_shared<const AttemptLaws>(laws));
  view.set(nullptr);

  RouteLeg stopped{.success_probability = 0.8, .attempt_seconds = 10.0};
  view.attempt_laws(0, kStart, stopped);
  EXPECT_DOUBLE_EQ(stopped.success_probability, 0.6);
  EXPECT_EQ(stopped.success_law, (std::vector<DurationPoint>{{10.0, 1.0}}));
  ASSERT_EQ(stopped.failure_law.size(), 2u);
  EXPECT_DOUBLE_EQ(stopped.failure_law[0].seconds, 5.0);
  EXPECT_DOUBLE_EQ(stopped.failure_law[0].weight, 0.5);  // 0.2 of 0.4
  EXPECT_DOUBLE_EQ(stopped.failure_law[1].seconds, 200.0);
  EXPECT_DOUBLE_EQ(stopped.failure_law[1].weight, 0.5);  // 0.8 x 0.25 of 0.4

  // The route's 0.8-quantile now reaches the stopped attempts; without them it stays short.
  RouteLeg plain{.success_probability = 0.8, .attempt_seconds = 10.0};
  view.attempt_laws(1, kStart, plain);
  EXPECT_DOUBLE_EQ(plain.success_probability, 0.8);
  EXPECT_EQ(plain.failure_law, (std::vector<DurationPoint>{{5.0, 1.0}}));
  const std::vector<RouteLeg> with{stopped};
  const std::vector<RouteLeg> without{plain};
  EXPECT_GE(TravelTimeDistribution::of_route(with).quantile(0.8).lower, 200.0);
  EXPECT_LE(TravelTimeDistribution::of_route(without).quantile(0.8).upper, 30.0);

  // A share of 1 (every attempt stopped) counts as kMaxStoppedShare: the edge still leads somewhere.
  laws.stopped[0].share = 1.0;
  view.set_attempt_laws(std::make_shared<const AttemptLaws>(laws));
  view.set(nullptr);
  RouteLeg all{.success_probability = 1.0, .attempt_seconds = 10.0};
  view.attempt_laws(0, kStart, all);
  EXPECT_DOUBLE_EQ(all.success_probability, 1.0 - LearnedEdgeModels::kMaxStoppedShare);
  EXPECT_EQ(all.failure_law, (std::vector<DurationPoint>{{200.0, 1.0}}));  // no failures: stopped only
}

}  // namespace
}  // namespace rondo::plan
