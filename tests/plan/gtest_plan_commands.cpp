// `rondo plan` end to end, in-process: a route through real node names on the G4S map with the
// distance prior, JSON output, exit code 2 naming an unknown node; with --models, the learned
// Witham Wharf models give the library's answer.
#include <gtest/gtest.h>

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <memory>

#include "app/cli_runner.h"
#include "rondo/core/document.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/edge_models.h"
#include "rondo/map/map_loader.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/travel_planner.h"

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

// Models fitted on the Witham Wharf logs, saved as `rondo learn` does, read back by `rondo plan`.
class PlanWithModels : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    map_ = std::make_unique<map::TopoMap>(map::load_map(kWitham).value());
    auto log = read_witham_logs("../shared/data/witham_wharf").value();
    const Time split = parse_time("2014-09-02T16:24:00Z").value();
    std::erase_if(log, [&](const Traversal& t) { return t.start >= split; });
    models_ = learn::EdgeModels::fit(edge_specs(*map_), log).value();
    file_ = std::filesystem::temp_directory_path() / fmt::format("rondo_plan_models_{}.json", ::getpid());
    ASSERT_TRUE(models_->save(file_));
  }
  static void TearDownTestSuite() { std::filesystem::remove(file_); }
  static inline const std::string kWitham = "examples/witham/map.yaml";
  static inline std::unique_ptr<map::TopoMap> map_;
  static inline std::shared_ptr<const learn::EdgeModels> models_;
  static inline std::filesystem::path file_;
};

TEST_F(PlanWithModels, PlansWithTheLearnedModels) {
  const std::string at = "2014-09-03T10:00:00Z";
  const auto r = run_cli({"plan", "--map", kWitham, "--models", file_.string(), "--from", "ChargingPoint", "--to",
                          "Kitchen", "--at", at, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["models"], "learned");
  EXPECT_EQ(j["learned_edges"].get<std::size_t>(), map_->edge_count());
  EXPECT_EQ(j["route"].front(), "ChargingPoint");
  EXPECT_EQ(j["route"].back(), "Kitchen");
  // The same answer as the library: LearnedEdgeModels over the (reloaded) models, exact solver.
  auto reloaded = learn::EdgeModels::load(file_).value();
  TravelPlanner oracle(*map_, std::make_shared<LearnedEdgeModels>(*map_, reloaded));
  const auto from = *map_->find_node("ChargingPoint");
  const auto to = *map_->find_node("Kitchen");
  const double expected = oracle.expected_seconds(from, to, parse_time(at).value());
  EXPECT_NEAR(j["expected_seconds"].get<double>(), expected, 1e-9 * expected);
  // Learned, not the prior: some step has p < 1 (the prior's is exactly 1).
  bool uncertain = false;
  for (const Json& s : j["steps"]) uncertain = uncertain || s["success_probability"].get<double>() < 1.0;
  EXPECT_TRUE(uncertain) << r.out;
  const auto prior = run_cli({"plan", "--map", kWitham, "--from", "ChargingPoint", "--to", "Kitchen", "--json"});
  EXPECT_NE(Json::parse(prior.out)["expected_seconds"].get<double>(), expected);
}

TEST_F(PlanWithModels, TableNamesTheModelsFile) {
  const auto r = run_cli({"plan", "--map", kWitham, "--models", file_.string(), "--from", "Station", "--to",
                          "Printer", "--at", "2014-09-03T10:00:00Z"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("learned (" + file_.string()), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Station -> "), std::string::npos) << r.out;
}

TEST_F(PlanWithModels, BadModelsOrMissingTimeAreBadInput) {
  const auto missing = run_cli({"plan", "--map", kWitham, "--models", "no/such/models.json", "--from", "Station",
                                "--to", "Printer", "--at", "2014-09-03T10:00:00Z"});
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
  EXPECT_NE(missing.err.find("--models"), std::string::npos) << missing.err;
  const auto no_time =
      run_cli({"plan", "--map", kWitham, "--models", file_.string(), "--from", "Station", "--to", "Printer"});
  EXPECT_EQ(no_time.exit_code, 2);
  EXPECT_NE(no_time.err.find("--at"), std::string::npos) << no_time.err;
}

}  // namespace
}  // namespace rondo::plan
