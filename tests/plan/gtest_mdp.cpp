// M_t construction: sanitising model outputs (no NaN, no negative times, p in [0, 1]), the
// crossing cost τ/p, and the distance prior read from the map geometry.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rondo/map/map_geometry.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/plan/mdp.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

using testing::small_map;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(Sanitize, TableOfModelOutputs) {
  struct Case {
    EdgeCrossing raw;
    double p;
    double tau;
    double crossing;
  };
  const Case cases[] = {
      {{1.0, 10.0}, 1.0, 10.0, 10.0},
      {{0.5, 10.0}, 0.5, 10.0, 20.0},
      {{0.0, 10.0}, 0.0, 10.0, kInfinity},
      {{-0.3, 10.0}, 0.0, 10.0, kInfinity},
      {{1.7, 10.0}, 1.0, 10.0, 10.0},
      {{kNaN, 10.0}, 0.0, 10.0, kInfinity},
      {{1.0, kNaN}, 1.0, kInfinity, kInfinity},
      {{1.0, kInfinity}, 1.0, kInfinity, kInfinity},
      {{1.0, -5.0}, 1.0, kMinAttemptSeconds, kMinAttemptSeconds},
      {{1.0, 0.0}, 1.0, kMinAttemptSeconds, kMinAttemptSeconds},
      {{1e-320, 10.0}, 1e-320, 10.0, kInfinity},  // τ/p overflows
  };
  for (const Case& c : cases) {
    const EdgeCrossing s = sanitize(c.raw);
    EXPECT_EQ(s.success_probability, c.p) << c.raw.success_probability << " " << c.raw.expected_seconds;
    EXPECT_EQ(s.expected_seconds, c.tau) << c.raw.success_probability << " " << c.raw.expected_seconds;
    EXPECT_EQ(expected_crossing_seconds(s), c.crossing) << c.raw.success_probability << " " << c.raw.expected_seconds;
  }
}

TEST(Mdp, FromOutcomesChecksTheCount) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B", "B>A"});
  EXPECT_FALSE(Mdp::from_outcomes(m, {{1.0, 1.0}}, Time{}).ok());
  auto mdp = Mdp::from_outcomes(m, {{1.0, 1.0}, {0.0, 2.0}}, Time{});
  ASSERT_TRUE(mdp.ok());
  EXPECT_TRUE(mdp->usable(0));
  EXPECT_FALSE(mdp->usable(1));
  EXPECT_EQ(mdp->node_count(), 2u);
}

TEST(Mdp, BuildReadsTheModelsAtTheGivenTime) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B"});
  Time seen{};
  FunctionEdgeModels models([&seen](map::EdgeIndex, Time t) {
    seen = t;
    return EdgeCrossing{0.25, 3.0};
  });
  const Time at = Time{} + hours(9);
  const Mdp mdp = Mdp::build(m, models, at);
  EXPECT_EQ(seen, at);
  EXPECT_EQ(mdp.time(), at);
  EXPECT_DOUBLE_EQ(mdp.expected_crossing_seconds(0), 12.0);
}

TEST(FunctionEdgeModels, SetMovesTheVersionOn) {
  FunctionEdgeModels models([](map::EdgeIndex, Time) { return EdgeCrossing{}; });
  const auto v = models.version();
  models.set([](map::EdgeIndex, Time) { return EdgeCrossing{0.5, 1.0}; });
  EXPECT_NE(models.version(), v);
  EXPECT_EQ(models.outcome(0, Time{}).success_probability, 0.5);
}

TEST(DistancePrior, UsesTheNominalTravelTimeAndThePriorProbability) {
  std::vector<map::Node> nodes = {{.name = "A", .pose = {0, 0, 0}}, {.name = "B", .pose = {3, 4, 0}}};
  std::vector<map::Edge> edges = {{.id = "A_B", .from = "A", .to = "B", .action = "move_base"},
                                  {.id = "B_A", .from = "B", .to = "A", .action = "doorPassing"}};
  const map::TopoMap m = map::TopoMap::build("m", std::move(nodes), std::move(edges)).value();
  const DistancePrior prior(m, {.success_probability = 0.8});
  EXPECT_DOUBLE_EQ(prior.outcome(0, Time{}).expected_seconds, 10.0);         // 5 m at 0.5 m/s
  EXPECT_DOUBLE_EQ(prior.outcome(1, Time{}).expected_seconds, 10.0 + 15.0);  // plus the door overhead
  EXPECT_DOUBLE_EQ(prior.outcome(1, Time{} + hours(5)).success_probability, 0.8);
  EXPECT_EQ(prior.version(), 0u);
  EXPECT_DOUBLE_EQ(prior.outcome(0, Time{}).expected_seconds, to_seconds(map::nominal_travel_time(m, 0)));
}

}  // namespace
}  // namespace rondo::plan
