// report.json's "live_estimates" (src/app/run_report.h): the relative errors of the estimates the
// executor used and of the snapshot's, on the journeys that arrived, with each estimate's sum over
// the sum of the actual times.
#include <gtest/gtest.h>

#include <vector>

#include "run_report.h"

namespace rondo {
namespace {

exec::NavigationRecord journey(double expected, double offline, double actual, bool arrived = true) {
  return {.task = "t",
          .start = from_unix_seconds(1'795'420'800),
          .expected = from_seconds(expected),
          .offline_expected = from_seconds(offline),
          .actual = from_seconds(actual),
          .arrived = arrived};
}

TEST(LiveEstimates, ScoresTheJourneysThatArrivedWithEachEstimatesSumOverTheActualTimes) {
  const std::vector<exec::NavigationRecord> n = {
      journey(100, 120, 100),       // used right, snapshot +0.2
      journey(50, 60, 100),         // used −0.5, snapshot −0.4
      journey(90, 99, 60),          // used +0.5, snapshot +0.65
      journey(10, 10, 999, false),  // stopped on the way: not scored
  };
  const Json j = app::live_estimates(n);
  EXPECT_EQ(j["used"]["count"].get<int>(), 3);
  EXPECT_NEAR(j["used"]["mean_abs"].get<double>(), (0.0 + 0.5 + 0.5) / 3, 1e-12);
  EXPECT_NEAR(j["offline_snapshot"]["mean_abs"].get<double>(), (0.2 + 0.4 + 0.65) / 3, 1e-12);
  EXPECT_NEAR(j["used"]["sum_ratio"].get<double>(), 240.0 / 260.0, 1e-12);
  EXPECT_NEAR(j["offline_snapshot"]["sum_ratio"].get<double>(), 279.0 / 260.0, 1e-12);
  EXPECT_LT(j["used"]["q10"].get<double>(), j["offline_snapshot"]["q10"].get<double>());
}

TEST(LiveEstimates, NoJourneyGivesZeros) {
  const Json j = app::live_estimates(std::vector<exec::NavigationRecord>{});
  EXPECT_EQ(j["used"]["count"].get<int>(), 0);
  EXPECT_EQ(j["used"]["sum_ratio"].get<double>(), 0.0);
}

}  // namespace
}  // namespace rondo
