// What a schedule assumes (src/exec/assumptions.h): the doors of the rooms its tasks enter, and
// the edges of its ways, on the office example and, against Floyd-Warshall, on random maps.
#include "assumptions.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "rondo/map/map_geometry.h"
#include "rondo/map/map_loader.h"

namespace rondo::exec {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

map::TopoMap office() { return map::load_map("examples/office/map.yaml").value(); }
map::NodeIndex at(const map::TopoMap& m, const std::string& name) { return *m.find_node(name); }

TEST(Assumptions, TheDoorsOfARoomAreTheOnesOnTheWayInFromTheDock) {
  const map::TopoMap m = office();
  const AssumptionMap a(m, at(m, "ChargingPoint"));
  EXPECT_THAT(a.doors_to(at(m, "A-120-Desk")), ElementsAre("A-120-door"));
  EXPECT_THAT(a.doors_to(at(m, "A-120")), ElementsAre("A-120-door"));
  EXPECT_TRUE(a.doors_to(at(m, "Hall-A-120")).empty());
  EXPECT_TRUE(a.doors_to(at(m, "Exit-East")).empty());
  EXPECT_TRUE(a.doors_to(at(m, "ChargingPoint")).empty());
}

TEST(Assumptions, APlanAssumesTheDoorsOfItsRoomsAndTheEdgesOfItsWays) {
  const map::TopoMap m = office();
  const AssumptionMap a(m, at(m, "ChargingPoint"));
  const Time t0{};
  const std::vector<PlannedStop> stops{
      {.task = "pickup", .start = at(m, "A-111-Table"), .end = at(m, "A-111-Table"), .until = t0 + minutes(5)},
      {.task = "drop", .start = at(m, "A-120-Desk"), .end = at(m, "A-120-Desk"), .until = t0 + minutes(9)}};
  const std::vector<Assumption> plan = a.for_plan(at(m, "ChargingPoint"), stops);
  std::vector<std::string> doors;
  for (const Assumption& x : plan)
    if (x.kind == Assumption::Kind::kDoorOpen) doors.push_back(x.task + ":" + x.what);
  EXPECT_THAT(doors, ElementsAre("pickup:A-111-door", "drop:A-120-door"));
  // The drop's way: out of A-111 (its door too: an edge, passable), along the hall, into A-120.
  std::vector<std::string> drop_edges;
  for (const Assumption& x : plan)
    if (x.kind == Assumption::Kind::kEdgePassable && x.task == "drop") drop_edges.push_back(x.what);
  ASSERT_FALSE(drop_edges.empty());
  EXPECT_EQ(drop_edges.front(), "A-111-Table_A-111");
  EXPECT_EQ(drop_edges.back(), "A-120_A-120-Desk");
  for (const Assumption& x : plan) EXPECT_EQ(x.until, x.task == "pickup" ? t0 + minutes(5) : t0 + minutes(9));
  const std::string text = describe(plan, TimeZone::utc());
  EXPECT_THAT(text, HasSubstr("pickup: door A-111-door open, 5 edges passable, until 00:05"));
  EXPECT_THAT(text, HasSubstr("; drop: door A-120-door open, "));
  EXPECT_EQ(describe({}, TimeZone::utc()), "");
}

TEST(Assumptions, NoWayMeansNoRoute) {
  const map::TopoMap m =
      map::TopoMap::build("two", {{.name = "A", .pose = {0, 0, 0}}, {.name = "B", .pose = {1, 0, 0}}},
                          {{.id = "A_B", .from = "A", .to = "B", .action = "move_base"}})
          .value();
  const AssumptionMap a(m, 0);
  EXPECT_EQ(a.route(0, 1).size(), 1u);
  EXPECT_TRUE(a.route(1, 0).empty());
  EXPECT_TRUE(a.route(1, 1).empty());
}

// A random map of up to 7 nodes and random edges, some through doors.
map::TopoMap random_map() {
  const auto n = *rc::gen::inRange<std::size_t>(1, 8);
  std::vector<map::Node> nodes;
  for (std::size_t i = 0; i < n; ++i)
    nodes.push_back({.name = "n" + std::to_string(i),
                     .pose = {*rc::gen::inRange(0, 50) * 1.0, *rc::gen::inRange(0, 50) * 1.0, 0}});
  std::vector<map::Edge> edges;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j || *rc::gen::inRange(0, 3) != 0) continue;
      map::Edge e{.id = "e" + std::to_string(i) + "_" + std::to_string(j), .from = nodes[i].name,
                  .to = nodes[j].name, .action = "move_base"};
      if (*rc::gen::inRange(0, 3) == 0) e.door = "d" + std::to_string(std::min(i, j)) + std::to_string(std::max(i, j));
      edges.push_back(e);
    }
  return map::TopoMap::build("random", nodes, edges).value();
}

RC_GTEST_PROP(AssumptionsProperty, RoutesAreShortestPathsAndRoomDoorsLieOnTheWayFromTheDock, ()) {
  const map::TopoMap m = random_map();
  const std::size_t n = m.node_count();
  const auto dock = *rc::gen::inRange<std::size_t>(0, n);
  const AssumptionMap a(m, dock);
  // The slow reference: Floyd-Warshall on the edge lengths.
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<std::vector<double>> d(n, std::vector<double>(n, kInf));
  for (std::size_t i = 0; i < n; ++i) d[i][i] = 0;
  for (map::EdgeIndex e = 0; e < m.edge_count(); ++e)
    d[m.from_index(e)][m.to_index(e)] = std::min(d[m.from_index(e)][m.to_index(e)], map::edge_length(m, e));
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) d[i][j] = std::min(d[i][j], d[i][k] + d[k][j]);
  for (std::size_t from = 0; from < n; ++from)
    for (std::size_t to = 0; to < n; ++to) {
      const std::vector<map::EdgeIndex> route = a.route(from, to);
      if (from == to || d[from][to] == kInf) {
        RC_ASSERT(route.empty());
        continue;
      }
      RC_ASSERT(!route.empty());
      map::NodeIndex here = from;
      double length = 0;
      for (map::EdgeIndex e : route) {
        RC_ASSERT(m.from_index(e) == here);
        here = m.to_index(e);
        length += map::edge_length(m, e);
      }
      RC_ASSERT(here == to);
      RC_ASSERT(std::abs(length - d[from][to]) <= 1e-9 * (1 + length));
    }
  for (std::size_t node = 0; node < n; ++node) {
    std::vector<std::string> on_way;
    for (map::EdgeIndex e : a.route(dock, node))
      if (m.edge(e).door) on_way.push_back(*m.edge(e).door);
    for (const std::string& door : a.doors_to(node))
      RC_ASSERT(std::find(on_way.begin(), on_way.end(), door) != on_way.end());
    RC_ASSERT(a.doors_to(node).size() <= on_way.size());
  }
}

}  // namespace
}  // namespace rondo::exec
