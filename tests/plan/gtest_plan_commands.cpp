// `rondo plan` end to end, in-process: a route through real node names on the G4S map with the
// distance prior, JSON output, and exit code 2 naming an unknown node.
#include <gtest/gtest.h>

#include "app/cli_runner.h"
#include "rondo/core/document.h"

namespace rondo::plan {
namespace {

using rondo::test::run_cli;

const std::string kMap = "../shared/data/maps/g4s_y2.tmap";

TEST(PlanCommand, PrintsARouteThroughRealNodes) {
  const auto r = run_cli({"plan", "--map", kMap, "--from", "WayPoint4", "--to", "ChargingPoint"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("WayPoint4 -> WayPoint3 ->"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("-> ChargingPoint ("), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("expected"), std::string::npos);
  EXPECT_NE(r.out.find("distance prior"), std::string::npos);
}

TEST(PlanCommand, Json) {
  const auto r = run_cli({"plan", "--map", kMap, "--from", "WayPoint4", "--to", "Station", "--at",
                          "2014-09-02T16:24:00Z", "--json", "--prior-probability", "0.8", "--budget", "2m"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_TRUE(j["reachable"].get<bool>());
  EXPECT_EQ(j["route"].front(), "WayPoint4");
  EXPECT_EQ(j["route"].back(), "Station");
  EXPECT_EQ(j["steps"].size() + 1, j["route"].size());
  EXPECT_EQ(j["depart"], "2014-09-02T16:24:00Z");
  EXPECT_GT(j["expected_seconds"].get<double>(), 0.0);
  ASSERT_EQ(j["quantiles"].size(), 5u);
  double previous = 0;
  for (const Json& q : j["quantiles"]) {
    EXPECT_LE(q["lower"].get<double>(), q["upper"].get<double>());
    EXPECT_GE(q["upper"].get<double>(), previous);
    previous = q["upper"].get<double>();
  }
  const double lower = j["probability_within_budget"]["lower"].get<double>();
  const double upper = j["probability_within_budget"]["upper"].get<double>();
  EXPECT_LE(0.0, lower);
  EXPECT_LE(lower, upper);
  EXPECT_LE(upper, 1.0);
}

TEST(PlanCommand, UnknownNodeIsBadInputNamingIt) {
  const auto r = run_cli({"plan", "--map", kMap, "--from", "WayPoint4", "--to", "Narnia"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'Narnia'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--to"), std::string::npos) << r.err;
  const auto from = run_cli({"plan", "--map", kMap, "--from", "Atlantis", "--to", "Station"});
  EXPECT_EQ(from.exit_code, 2);
  EXPECT_NE(from.err.find("'Atlantis'"), std::string::npos) << from.err;
}

TEST(PlanCommand, BadTimeAndMissingMapAreBadInput) {
  EXPECT_EQ(run_cli({"plan", "--map", kMap, "--from", "WayPoint4", "--to", "Station", "--at", "noon"}).exit_code, 2);
  EXPECT_EQ(run_cli({"plan", "--map", "no/such/map.tmap", "--from", "A", "--to", "B"}).exit_code, 2);
}

TEST(PlanCommand, ModelsAreNotSupportedYet) {
  const auto r = run_cli({"plan", "--map", kMap, "--models", "models.json", "--from", "WayPoint4", "--to", "Station"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("not supported yet"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace rondo::plan
