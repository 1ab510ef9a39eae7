// TopoMap: building, lookups by name and id, adjacency, value semantics and equality.
#include "rondo/map/topo_map.h"

#include <gtest/gtest.h>

#include "map_test_support.h"

namespace rondo::map {
namespace {

using testing::build_or_fail;
using testing::edge;
using testing::node_at;

TopoMap triangle() {
  return build_or_fail({node_at("A", 0, 0), node_at("B", 1, 0), node_at("C", 0, 1)},
                       {edge("A", "B"), edge("B", "C"), edge("C", "A"), edge("A", "C", "doorPassing")});
}

TEST(TopoMap, EmptyMapHasNothing) {
  const TopoMap map;
  EXPECT_EQ(map.node_count(), 0u);
  EXPECT_EQ(map.edge_count(), 0u);
  EXPECT_FALSE(map.find_node("A").has_value());
  EXPECT_EQ(map.name(), "");
}

TEST(TopoMap, FindsNodesAndEdgesByName) {
  const TopoMap map = triangle();
  ASSERT_EQ(map.node_count(), 3u);
  ASSERT_EQ(map.edge_count(), 4u);
  EXPECT_EQ(map.find_node("A"), 0u);
  EXPECT_EQ(map.find_node("C"), 2u);
  EXPECT_FALSE(map.find_node("D").has_value());
  EXPECT_FALSE(map.find_node("").has_value());
  EXPECT_EQ(map.find_edge("C_A"), 2u);
  EXPECT_FALSE(map.find_edge("A_A").has_value());
  EXPECT_EQ(map.name(), "test");
}

TEST(TopoMap, EdgeEndsAreDenseIndices) {
  const TopoMap map = triangle();
  const EdgeIndex bc = *map.find_edge("B_C");
  EXPECT_EQ(map.from_index(bc), 1u);
  EXPECT_EQ(map.to_index(bc), 2u);
}

TEST(TopoMap, OutAndInEdgesFollowEdgeOrder) {
  const TopoMap map = triangle();
  const auto out_a = map.out_edges(0);
  ASSERT_EQ(out_a.size(), 2u);
  EXPECT_EQ(map.edge(out_a[0]).id, "A_B");
  EXPECT_EQ(map.edge(out_a[1]).id, "A_C");
  const auto in_c = map.in_edges(2);
  ASSERT_EQ(in_c.size(), 2u);
  EXPECT_EQ(map.edge(in_c[0]).id, "B_C");
  EXPECT_EQ(map.edge(in_c[1]).id, "A_C");
  EXPECT_EQ(map.out_edges(1).size(), 1u);
}

TEST(TopoMap, NodeWithoutEdgesHasEmptyAdjacency) {
  const TopoMap map = build_or_fail({node_at("A", 0, 0), node_at("Alone", 5, 5)}, {});
  EXPECT_TRUE(map.out_edges(1).empty());
  EXPECT_TRUE(map.in_edges(1).empty());
}

TEST(TopoMap, OutOfRangeIndexIsMisuseNotUndefinedBehaviour) {
  const TopoMap map = triangle();
  EXPECT_THROW((void)map.out_edges(3), std::out_of_range);
  EXPECT_THROW((void)map.node(3), std::out_of_range);
  EXPECT_THROW((void)map.edge(4), std::out_of_range);
}

TEST(TopoMap, DesignatedInitialisersWorkWithoutWarnings) {
  // The header's usage example, compiled with -Wextra -Werror.
  std::vector<Node> nodes = {{.name = "Kitchen", .pose = {0, 0, 0}}, {.name = "Office", .pose = {4, 3, 1.57}}};
  std::vector<Edge> edges = {
      {.id = "Kitchen_Office", .from = "Kitchen", .to = "Office", .action = "move_base", .top_speed = 0.55}};
  auto map = TopoMap::build("flat", std::move(nodes), std::move(edges));
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_DOUBLE_EQ(map->node(0).xy_goal_tolerance, kDefaultXyGoalTolerance);
  EXPECT_DOUBLE_EQ(map->node(0).yaw_goal_tolerance, kDefaultYawGoalTolerance);
  EXPECT_FALSE(map->edge(0).door.has_value());
}

TEST(TopoMap, CopiesAreEqualAndIndependent) {
  const TopoMap map = triangle();
  TopoMap copy = map;
  EXPECT_EQ(copy, map);
  TopoMap moved = std::move(copy);
  EXPECT_EQ(moved, map);
  EXPECT_EQ(moved.find_node("B"), 1u);
  EXPECT_EQ(moved.out_edges(0).size(), 2u);
}

TEST(TopoMap, EqualityLooksAtEveryField) {
  const auto base_nodes = std::vector<Node>{node_at("A", 0, 0), node_at("B", 1, 0)};
  const auto base_edges = std::vector<Edge>{edge("A", "B")};
  const TopoMap base = build_or_fail(base_nodes, base_edges);

  struct Case {
    const char* what;
    std::function<void(std::vector<Node>&, std::vector<Edge>&, std::string&)> change;
  };
  const std::vector<Case> cases = {
      {"map name", [](auto&, auto&, std::string& name) { name = "other"; }},
      {"node name",
       [](auto& n, auto& e, auto&) {
         n[1].name = "C";
         e[0].to = "C";
       }},
      {"pose x", [](auto& n, auto&, auto&) { n[0].pose.x = 1e-12; }},
      {"yaw", [](auto& n, auto&, auto&) { n[0].pose.yaw = 0.1; }},
      {"xy tolerance", [](auto& n, auto&, auto&) { n[0].xy_goal_tolerance = 0.2; }},
      {"yaw tolerance", [](auto& n, auto&, auto&) { n[0].yaw_goal_tolerance = 0.2; }},
      {"influence",
       [](auto& n, auto&, auto&) {
         n[0].influence.push_back({1, 1});
       }},
      {"meta",
       [](auto& n, auto&, auto&) {
         n[0].meta = Json{{"description", "x"}};
       }},
      {"edge id", [](auto&, auto& e, auto&) { e[0].id = "other"; }},
      {"action", [](auto&, auto& e, auto&) { e[0].action = "docking"; }},
      {"top speed", [](auto&, auto& e, auto&) { e[0].top_speed = 0.3; }},
      {"door", [](auto&, auto& e, auto&) { e[0].door = "d1"; }},
      {"node order", [](auto& n, auto&, auto&) { std::swap(n[0], n[1]); }},
  };
  for (const Case& c : cases) {
    auto nodes = base_nodes;
    auto edges = base_edges;
    std::string name = "test";
    c.change(nodes, edges, name);
    const TopoMap changed = build_or_fail(nodes, edges, name);
    EXPECT_FALSE(changed == base) << c.what;
  }
}

TEST(TopoMap, BuildRejectsAnInvalidMapNamingTheProblem) {
  auto map = TopoMap::build("m", {node_at("A", 0, 0)}, {edge("A", "B")});
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(map.error().message, "edges[0] 'A_B': to: no node named 'B'");
}

TEST(TopoMap, BuildCountsFurtherProblems) {
  auto map = TopoMap::build("m", {node_at("A", 0, 0), node_at("A", 1, 0)}, {edge("A", "B"), edge("A", "A")});
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.error().message, "nodes[1] 'A': name: node 'A' is already defined by nodes[0] (and 2 more problems)");
}

TEST(TopoMap, BuildRejectsAMapNameThatIsNotUtf8) {
  auto map = TopoMap::build("caf\xe9", {node_at("A", 0, 0)}, {});
  ASSERT_FALSE(map.ok());
  EXPECT_EQ(map.error().message, "the map name must be UTF-8 text");
}

}  // namespace
}  // namespace rondo::map
