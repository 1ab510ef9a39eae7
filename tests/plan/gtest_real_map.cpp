// The planner on the G4S map of the published deployment (tests run from the project root), with
// the distance prior: routes through real node names, and expected times equal to the sum of the
// nominal edge times along them.
#include <gtest/gtest.h>

#include <memory>

#include "rondo/map/map_geometry.h"
#include "rondo/map/map_loader.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/plan/value_iteration.h"

namespace rondo::plan {
namespace {

const char* const kMap = "../shared/data/maps/g4s_y2.tmap";

TEST(RealMap, G4sRoutesThroughRealNodes) {
  auto m = map::load_map(kMap);
  ASSERT_TRUE(m.ok()) << m.error().message;
  const auto from = m->find_node("WayPoint4");
  const auto to = m->find_node("ChargingPoint");
  ASSERT_TRUE(from && to);
  const DistancePrior prior(*m);
  const Mdp mdp = Mdp::build(*m, prior, Time{});
  const Policy policy = ExactSolver{}.solve(mdp, *to).value().policy;
  const auto route = policy.route(*from);
  ASSERT_FALSE(route.empty());
  EXPECT_EQ(route.front().from, *from);
  EXPECT_EQ(route.back().to, *to);
  double sum = 0;
  for (const PolicyStep& s : route) {
    EXPECT_EQ(m->edge(s.edge).from, m->node(s.from).name);
    EXPECT_EQ(m->edge(s.edge).to, m->node(s.to).name);
    sum += to_seconds(map::nominal_travel_time(*m, s.edge));
  }
  EXPECT_NEAR(policy.expected_seconds(*from), sum, 1e-6);
  EXPECT_EQ(m->node(route.front().to).name, "WayPoint3");  // WayPoint4's only edge
  // Value iteration agrees on every node of the real map.
  const Policy vi = ValueIteration({.tolerance = 1e-10}).solve(mdp, *to).value().policy;
  for (NodeIndex i = 0; i < m->node_count(); ++i) {
    if (policy.expected_seconds(i) == kInfinity) {
      EXPECT_EQ(vi.expected_seconds(i), kInfinity);
    } else {
      EXPECT_NEAR(vi.expected_seconds(i), policy.expected_seconds(i), 1e-6 * std::max(1.0, policy.expected_seconds(i)));
    }
  }
}

}  // namespace
}  // namespace rondo::plan
