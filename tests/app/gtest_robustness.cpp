// `rondo eval robustness`: its seeds, what it reads from a report, and a short evaluation through
// the command line (the long ones are measurements: docs/scheduling.md, "Slack sized by risk").
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.h"
#include "robustness.h"

namespace rondo::app {
namespace {

using ::testing::HasSubstr;

TEST(Robustness, SeedsAreACountARangeOrAList) {
  EXPECT_EQ(*parse_seeds("3"), (std::vector<std::uint64_t>{1, 2, 3}));
  EXPECT_EQ(*parse_seeds("101-103"), (std::vector<std::uint64_t>{101, 102, 103}));
  EXPECT_EQ(*parse_seeds("4,1,9"), (std::vector<std::uint64_t>{4, 1, 9}));
  for (const char* bad : {"", "0", "x", "5-2", "1-", "1,,2", "1-2000"}) EXPECT_FALSE(parse_seeds(bad).ok()) << bad;
}

// A seed is what `rondo run --seed` and a deployment's `seed:` take, 0 to 2^63 - 1: past it, a
// seed is refused (it was taken, and a range ending at 2^64 - 1 never ended).
TEST(Robustness, SeedsPastTheLargestSeedAreRefused) {
  EXPECT_EQ(*parse_seeds("9223372036854775806-9223372036854775807"),
            (std::vector<std::uint64_t>{9223372036854775806u, 9223372036854775807u}));
  for (const char* bad : {"9223372036854775808", "9223372036854775807-9223372036854775808", "1,9223372036854775808",
                          "-1", "1,-2", "18446744073709551615-18446744073709551615"}) {
    const auto seeds = parse_seeds(bad);
    ASSERT_FALSE(seeds.ok()) << bad;
    EXPECT_THAT(seeds.error().message, HasSubstr("is not a seed (a whole number from 0 to 9223372036854775807)"));
  }
}

TEST(Robustness, AReportIsReadByReason) {
  const Json report = Json::parse(R"({
    "tasks": {"added": 20, "completed": 11,
              "failed": {"too late": 2, "navigation overrun": 3, "action failed": 1, "charging": 1},
              "dropped": {"charging": 2, "does not fit": 1}, "cancelled": {}},
    "time_s": {"waiting": 360.0},
    "battery": {"lowest": 0.25, "days_flat": 1}})");
  const RunFiguresSummary s = summarize_report(report);
  EXPECT_EQ(s.added, 20);
  EXPECT_EQ(s.completed, 11);
  EXPECT_EQ(s.too_late, 2);
  EXPECT_EQ(s.navigation_overrun, 3);
  EXPECT_EQ(s.battery, 1 + 2 + 1);  // failed and dropped for charging, and the day it ran flat
  EXPECT_EQ(s.other_failures, 1);
  EXPECT_EQ(s.dropped, 1);
  EXPECT_DOUBLE_EQ(s.waiting_s, 360.0);
  EXPECT_DOUBLE_EQ(s.lowest_charge, 0.25);
}

TEST(Robustness, OneDayOfTheExampleUnderEveryVariantWithRatiosAgainstExpectedValues) {
  const auto r = test::run_cli({"eval", "robustness", "examples/g4s/deployment.yaml", "--days", "1", "--seeds", "1",
                                "--alphas", "0.2", "--jobs", "2", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 5U);  // expected, alpha 0.2, idle charging, planned charging, along the route
  EXPECT_EQ(j["rows"][0]["variant"], "expected");
  EXPECT_DOUBLE_EQ(j["rows"][0]["completed_ratio"].get<double>(), 1.0);
  EXPECT_EQ(j["rows"][1]["alpha"].get<double>(), 0.2);
  EXPECT_EQ(j["rows"][3]["variant"], "planned charging");
  EXPECT_EQ(j["rows"][4]["variant"], "along route 30s");
  EXPECT_EQ(j["runs"].size(), 5U);
  for (const Json& run : j["runs"]) EXPECT_GT(run["added"].get<int>(), 0);
  // The same seed and variant give the same figures: the evaluation is deterministic.
  const auto again = test::run_cli({"eval", "robustness", "examples/g4s/deployment.yaml", "--days", "1", "--seeds",
                                    "1", "--alphas", "0.2", "--jobs", "1", "--json"});
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(Json::parse(again.out)["rows"], j["rows"]);
}

TEST(Robustness, VariantsRunsTheNamedOnesBesideTheBaseline) {
  const auto r = test::run_cli({"eval", "robustness", "examples/g4s/deployment.yaml", "--days", "1", "--seeds", "1",
                                "--route-thresholds", "30,120", "--variants", "along route 120s", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 2U);
  EXPECT_EQ(j["rows"][0]["variant"], "expected");
  EXPECT_EQ(j["rows"][1]["variant"], "along route 120s");
}

TEST(Robustness, BadArgumentsAreExitCode2) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"eval", "robustness", "examples/g4s/deployment.yaml", "--seeds", "x"},
        std::vector<std::string>{"eval", "robustness", "examples/g4s/deployment.yaml", "--alphas", "0.9"},
        std::vector<std::string>{"eval", "robustness", "examples/g4s/deployment.yaml", "--route-thresholds", "0"},
        std::vector<std::string>{"eval", "robustness", "no-such-deployment.yaml"}}) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args.back();
    EXPECT_THAT(r.err, HasSubstr("error")) << args.back();
  }
}

}  // namespace
}  // namespace rondo::app
