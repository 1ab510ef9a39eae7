// evaluate_travel (the paper's Table I): on a small log whose true travel times are known in
// closed form, the static route and origin-destination estimates are exact, the prior is off by a
// known amount, online models catch up with a change that offline ones miss, and the counts and
// JSON shape hold. The real Witham Wharf table is checked in gtest_eval_travel_command.cpp.
#include <gtest/gtest.h>

#include "rondo/plan/travel_evaluation.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

using testing::small_map;

const Time kT0 = Time{} + hours(24 * 16000);

Traversal attempt(const std::string& from, const std::string& to, Time start, double seconds, bool success) {
  return {.edge_id = from + "_" + to, .from = from, .to = to, .start = start, .duration = from_seconds(seconds),
          .success = success};
}

// One journey A -> B -> C per hour: A_B takes 10 s; B_C takes 20 s and fails once first unless
// `reliable`. Ground truth 50 s (30 s when reliable), no pauses.
void add_journey(std::vector<Traversal>& log, Time t, bool reliable) {
  log.push_back(attempt("A", "B", t, 10, true));
  if (!reliable) log.push_back(attempt("B", "C", t + seconds(10), 20, false));
  log.push_back(attempt("B", "C", t + seconds(reliable ? 10 : 30), 20, true));
}

struct Fixture {
  map::TopoMap map = small_map({"A", "B", "C"}, {"A>B", "B>C"});
  std::vector<Traversal> log;
  TravelEvaluationOptions options;
  Fixture(bool reliable_after_split) {
    for (int h = 0; h < 48; ++h) add_journey(log, kT0 + hours(h), false);
    for (int h = 48; h < 72; ++h) add_journey(log, kT0 + hours(h), reliable_after_split);
    options.trainings = {{"none", kT0, kT0}, {"all", kT0, kT0 + hours(48)}};
    options.test = {"test", kT0 + hours(48), kT0 + hours(72)};
    options.families = {learn::EdgeFamily::kStatic};
  }
  const TravelErrorRow& row(const TravelEvaluation& e, const std::string& training, const std::string& protocol,
                            const std::string& estimate) {
    for (const auto& r : e.rows)
      if (r.training == training && r.protocol == protocol && r.estimate == estimate) return r;
    throw std::runtime_error("no such row");
  }
};

TEST(ErrorSummary, QuantilesMeanAbsAndStd) {
  const ErrorSummary s = summarize_errors({2.0, -1.0, 0.0, 1.0, 3.0});
  EXPECT_EQ(s.count, 5u);
  EXPECT_DOUBLE_EQ(s.q10, -0.6);  // position 0.4 between -1 and 0
  EXPECT_DOUBLE_EQ(s.q25, 0.0);
  EXPECT_DOUBLE_EQ(s.q75, 2.0);
  EXPECT_DOUBLE_EQ(s.q90, 2.6);
  EXPECT_DOUBLE_EQ(s.mean_abs, 7.0 / 5.0);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(2.5));
  EXPECT_EQ(summarize_errors({}).count, 0u);
  EXPECT_EQ(summarize_errors({4.0}).std, 0.0);
}

TEST(TravelEvaluation, StaticModelsAreExactOnAStationaryLogAndThePriorIsOffByItsDistance) {
  Fixture f(false);
  const TravelEvaluation e = evaluate_travel(f.map, f.log, f.options).value();
  EXPECT_EQ(e.journeys, 24u);
  EXPECT_EQ(e.rows.size(), 2u * 2u * 2u);  // trainings × protocols × estimates (one family)
  for (const char* estimate : {"route", "od"}) {
    const TravelErrorRow& r = f.row(e, "all", "offline", estimate);
    EXPECT_EQ(r.model, "static");
    EXPECT_EQ(r.errors.count, 24u);
    // B_C: p = 1/2, τ = 20 s, so 40 s expected; A_B 10 s: exactly the 50 s it takes.
    EXPECT_NEAR(r.errors.mean_abs, 0.0, 1e-12) << estimate;
    // The prior: nodes 1 m apart at 0.5 m/s, p = 1: 4 s for a 50 s journey.
    const TravelErrorRow& prior = f.row(e, "none", "offline", estimate);
    EXPECT_NEAR(prior.errors.mean_abs, 46.0 / 50.0, 1e-12) << estimate;
    EXPECT_NEAR(prior.errors.q10, -46.0 / 50.0, 1e-12) << estimate;
  }
}

TEST(TravelEvaluation, OnlineModelsFollowAChangeThatOfflineOnesMiss) {
  Fixture f(true);  // after the split B_C never fails: the journeys take 30 s
  const TravelEvaluation e = evaluate_travel(f.map, f.log, f.options).value();
  const TravelErrorRow& offline = f.row(e, "all", "offline", "route");
  const TravelErrorRow& online = f.row(e, "all", "online", "route");
  EXPECT_NEAR(offline.errors.mean_abs, 20.0 / 30.0, 1e-12);  // still 50 s
  EXPECT_LT(online.errors.mean_abs, offline.errors.mean_abs);
  // Online, the first test journey has seen nothing new (the static running mean: 20 / 30 off);
  // the last has seen 23 reliable crossings: p = 71/119, (10 + 20 / p − 30) / 30 off.
  EXPECT_NEAR(online.errors.q90, 20.0 / 30.0, 0.05);
  const double last = (10.0 + 20.0 * 119.0 / 71.0 - 30.0) / 30.0;
  EXPECT_GT(online.errors.q10, last);
  EXPECT_LT(online.errors.q10, last + 0.02);
}

// A fleet of two, one robot half as fast as the other, their journeys interleaved (each a minute
// after the other's): with its pace learned, each robot's journey is estimated as its own; pooled
// without it, both would be a third off. Not exactly: the pace's ridge (4 pseudo-attempts against
// 96 attempts each in the training window) shrinks the log-ratio by 4 %, 1.4 % on each estimate.
TEST(TravelEvaluation, EachRobotsJourneyIsEstimatedAtItsOwnPace) {
  Fixture f(true);
  f.log.clear();
  for (int h = 0; h < 72; ++h) {
    for (const auto& [robot, slow] : {std::pair{"fast", 1.0}, std::pair{"slow", 2.0}}) {
      const Time t = kT0 + hours(h) + minutes(slow > 1 ? 1 : 0);
      for (auto a :
           {attempt("A", "B", t, 10 * slow, true), attempt("B", "C", t + from_seconds(10 * slow), 20 * slow, true)}) {
        a.robot = robot;
        f.log.push_back(a);
      }
    }
  }
  const TravelEvaluation e = evaluate_travel(f.map, f.log, f.options).value();
  EXPECT_EQ(e.journeys, 48u);  // 24 test hours, two robots: none chained across them
  for (const char* protocol : {"offline", "online"})
    for (const char* estimate : {"route", "od"})
      EXPECT_NEAR(f.row(e, "all", protocol, estimate).errors.mean_abs, 0.014, 0.002) << protocol << " " << estimate;
}

TEST(TravelEvaluation, CountsFailedAndOffMapJourneysAndRejectsAnEmptyTest) {
  Fixture f(false);
  f.log.push_back(attempt("A", "B", kT0 + hours(60) + minutes(30), 10, false));  // gave up
  f.log.push_back(attempt("C", "Z", kT0 + hours(61) + minutes(30), 10, true));   // not in the map
  const TravelEvaluation e = evaluate_travel(f.map, f.log, f.options).value();
  EXPECT_EQ(e.test_journeys, 26u);
  EXPECT_EQ(e.failed, 1u);
  EXPECT_EQ(e.off_map, 1u);
  EXPECT_EQ(e.journeys, 24u);
  const Json j = travel_evaluation_to_json(e);
  EXPECT_EQ(j["journeys"], 24);
  ASSERT_EQ(j["rows"].size(), e.rows.size());
  for (const char* key : {"training", "model", "protocol", "estimate", "q10", "q25", "q75", "q90", "mean_abs", "std", "count"})
    EXPECT_TRUE(j["rows"][0].contains(key)) << key;
  f.options.test = {"test", kT0 + hours(100), kT0 + hours(200)};
  const auto none = evaluate_travel(f.map, f.log, f.options);
  ASSERT_FALSE(none);
  EXPECT_NE(none.error().message.find("no journey"), std::string::npos);
}

TEST(TravelEvaluation, EveryFamilyGivesFiniteRows) {
  Fixture f(false);
  f.options.families = {learn::EdgeFamily::kStatic, learn::EdgeFamily::kFremen, learn::EdgeFamily::kEpisode};
  const TravelEvaluation e = evaluate_travel(f.map, f.log, f.options).value();
  EXPECT_EQ(e.rows.size(), 2u * 3u * 2u * 2u);
  for (const auto& r : e.rows) {
    EXPECT_TRUE(std::isfinite(r.errors.mean_abs)) << r.model << " " << r.training;
    EXPECT_EQ(r.errors.count, 24u);
  }
}

}  // namespace
}  // namespace rondo::plan
