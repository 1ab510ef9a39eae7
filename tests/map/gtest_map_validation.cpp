// The map rules (find_map_problems, describe) and the connectivity warnings.
#include "rondo/map/map_validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "map_test_support.h"

namespace rondo::map {
namespace {

using testing::build_or_fail;
using testing::edge;
using testing::node_at;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct ProblemCase {
  const char* what;
  std::vector<Node> nodes;
  std::vector<Edge> edges;
  std::string expected;  // describe() of the first problem
};

Edge with_speed(Edge e, double speed) {
  e.top_speed = speed;
  return e;
}
Edge with_id(Edge e, std::string id) {
  e.id = std::move(id);
  return e;
}
Edge with_door(Edge e, std::string door) {
  e.door = std::move(door);
  return e;
}
Node with_tolerances(Node n, double xy, double yaw) {
  n.xy_goal_tolerance = xy;
  n.yaw_goal_tolerance = yaw;
  return n;
}
Node with_capacity(Node n, int capacity) {
  n.capacity = capacity;
  return n;
}
Edge with_narrow(Edge e, Narrow narrow) {
  e.narrow = narrow;
  return e;
}
Node with_vertex(Node n, double x, double y) {
  n.influence.push_back({x, y});
  return n;
}

class MapProblems : public ::testing::TestWithParam<ProblemCase> {};

TEST_P(MapProblems, FirstProblemIsDescribed) {
  const ProblemCase& c = GetParam();
  const auto problems = find_map_problems(c.nodes, c.edges);
  ASSERT_FALSE(problems.empty()) << c.what;
  EXPECT_EQ(describe(problems.front(), c.nodes, c.edges), c.expected) << c.what;
  EXPECT_FALSE(TopoMap::build("m", c.nodes, c.edges).ok()) << c.what;
}

const Node kA = node_at("A", 0, 0);
const Node kB = node_at("B", 1, 0);

INSTANTIATE_TEST_SUITE_P(
    Rules, MapProblems,
    ::testing::Values(
        ProblemCase{"duplicate node",
                    {kA, kB, node_at("A", 5, 5)},
                    {},
                    "nodes[2] 'A': name: node 'A' is already defined by nodes[0]"},
        ProblemCase{"empty name", {node_at("", 0, 0)}, {}, "nodes[0]: name: a node name must not be empty"},
        ProblemCase{"control character",
                    {node_at("A\nB", 0, 0)},
                    {},
                    "nodes[0] 'A?B': name: a node name must not contain control characters"},
        ProblemCase{
            "not UTF-8", {node_at("caf\xe9", 0, 0)}, {}, "nodes[0] 'caf\xe9': name: a node name must be UTF-8 text"},
        ProblemCase{"NaN x", {node_at("A", kNan, 0)}, {}, "nodes[0] 'A': pose.x: must be a finite number"},
        ProblemCase{"infinite y", {node_at("A", 0, -kInf)}, {}, "nodes[0] 'A': pose.y: must be a finite number"},
        ProblemCase{"NaN yaw", {node_at("A", 0, 0, kNan)}, {}, "nodes[0] 'A': pose.yaw: must be a finite number"},
        ProblemCase{"negative xy tolerance",
                    {with_tolerances(kA, -0.1, 0.1)},
                    {},
                    "nodes[0] 'A': xy_goal_tolerance: must be a finite number of metres, 0 or more"},
        ProblemCase{"infinite yaw tolerance",
                    {with_tolerances(kA, 0.1, kInf)},
                    {},
                    "nodes[0] 'A': yaw_goal_tolerance: must be a finite number of radians, 0 or more"},
        ProblemCase{"NaN vertex",
                    {with_vertex(with_vertex(kA, 1, 1), kNan, 0)},
                    {},
                    "nodes[0] 'A': influence[1]: vertex coordinates must be finite numbers"},
        ProblemCase{"unknown target", {kA, kB}, {edge("A", "C")}, "edges[0] 'A_C': to: no node named 'C'"},
        ProblemCase{
            "unknown source", {kA, kB}, {edge("A", "B"), edge("X", "B")}, "edges[1] 'X_B': from: no node named 'X'"},
        ProblemCase{"self-loop",
                    {kA, kB},
                    {edge("B", "B")},
                    "edges[0] 'B_B': to: the edge leads from node 'B' back to itself (self-loops are not allowed)"},
        ProblemCase{"duplicate edge id",
                    {kA, kB},
                    {edge("A", "B"), with_id(edge("B", "A"), "A_B")},
                    "edges[1] 'A_B': id: edge id 'A_B' is already used by edges[0]"},
        ProblemCase{
            "empty edge id", {kA, kB}, {with_id(edge("A", "B"), "")}, "edges[0]: id: an edge id must not be empty"},
        ProblemCase{
            "empty action", {kA, kB}, {edge("A", "B", "")}, "edges[0] 'A_B': action: the action must not be empty"},
        ProblemCase{"negative speed",
                    {kA, kB},
                    {with_speed(edge("A", "B"), -0.5)},
                    "edges[0] 'A_B': top_speed: must be a finite speed above 0 m/s, not -0.5"},
        ProblemCase{"zero speed",
                    {kA, kB},
                    {with_speed(edge("A", "B"), 0)},
                    "edges[0] 'A_B': top_speed: must be a finite speed above 0 m/s, not 0"},
        ProblemCase{"NaN speed",
                    {kA, kB},
                    {with_speed(edge("A", "B"), kNan)},
                    "edges[0] 'A_B': top_speed: must be a finite speed above 0 m/s, not nan"},
        ProblemCase{"empty door",
                    {kA, kB},
                    {with_door(edge("A", "B"), "")},
                    "edges[0] 'A_B': door: a door id must not be empty"},
        ProblemCase{"capacity 0",
                    {kA, with_capacity(kB, 0)},
                    {},
                    "nodes[1] 'B': capacity: must be a whole number of robots from 1 to 1000, not 0"},
        ProblemCase{"capacity too large",
                    {with_capacity(kA, 1001)},
                    {},
                    "nodes[0] 'A': capacity: must be a whole number of robots from 1 to 1000, not 1001"}));

TEST(MapProblems, AllProblemsAreListedInOrder) {
  const std::vector<Node> nodes = {kA, node_at("A", kNan, 0)};
  const std::vector<Edge> edges = {edge("A", "Z"), edge("A", "A")};
  const auto problems = find_map_problems(nodes, edges);
  ASSERT_EQ(problems.size(), 4u);
  EXPECT_EQ(problems[0].field, "name");
  EXPECT_EQ(problems[1].field, "pose.x");
  EXPECT_EQ(problems[2].subject, MapProblem::Subject::kEdge);
  EXPECT_EQ(problems[2].field, "to");
  EXPECT_EQ(problems[3].index, 1u);
}

TEST(MapProblems, AValidMapHasNone) {
  Node a = with_vertex(kA, 0.5, 0.5);
  a.meta = Json{{"description", "kitchen"}};
  EXPECT_TRUE(find_map_problems({a, kB}, {with_door(with_speed(edge("A", "B"), 0.55), "d"), edge("B", "A")}).empty());
}

TEST(MapProblems, LongNamesAreShortenedInMessages) {
  const std::string long_name(200, 'x');
  const auto problems = find_map_problems({kA}, {edge("A", long_name)});
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_EQ(problems[0].message, "no node named '" + std::string(60, 'x') + "...'");
}

TEST(MapWarnings, StronglyConnectedMapHasNone) {
  const TopoMap map = build_or_fail({kA, kB}, {edge("A", "B"), edge("B", "A")});
  EXPECT_TRUE(map_warnings(map).empty());
  EXPECT_EQ(strongly_connected_components(map).size(), 1u);
}

TEST(MapWarnings, SingleNodeIsStronglyConnected) {
  EXPECT_TRUE(map_warnings(build_or_fail({kA}, {})).empty());
}

TEST(MapWarnings, NamesDeadEndsUnreachableAndIsolatedNodes) {
  // A <-> B is the main group; B -> Lift is a dead end; In -> A cannot be reached; Island has no edges.
  const TopoMap map = build_or_fail({kA, kB, node_at("Lift", 2, 0), node_at("In", 3, 0), node_at("Island", 9, 9)},
                                    {edge("A", "B"), edge("B", "A"), edge("B", "Lift"), edge("In", "A")});
  const auto warnings = map_warnings(map);
  ASSERT_EQ(warnings.size(), 4u);
  EXPECT_EQ(warnings[0],
            "the map is not strongly connected: 4 groups of nodes; the largest holds 2 of the 5 nodes (around 'A'), "
            "and the robot cannot go back and forth between it and the others");
  EXPECT_EQ(warnings[1], "node 'Lift' is a dead end: the robot cannot get back from it to the largest group");
  EXPECT_EQ(warnings[2], "node 'In' cannot be reached from the largest group of nodes");
  EXPECT_EQ(warnings[3], "node 'Island' is cut off: no path leads between it and the largest group");
}

TEST(MapWarnings, NamesAPassageWhoseDirectionsAreMarkedDifferently) {
  const TopoMap map =
      build_or_fail({kA, kB, node_at("C", 2, 0)},
                    {with_narrow(edge("A", "B"), Narrow::kOneWay), edge("B", "A"),
                     with_narrow(edge("B", "C"), Narrow::kSingle), with_narrow(edge("C", "B"), Narrow::kSingle)});
  const auto warnings = map_warnings(map);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_EQ(warnings[0],
            "edges 'A_B' (narrow: one_way) and 'B_A' (narrow: none) lead between the same two nodes: the simulator "
            "takes the passage as one_way");
  EXPECT_EQ(passage_narrow(map, 1), Narrow::kOneWay);
  EXPECT_EQ(passage_narrow(map, 2), Narrow::kSingle);
}

TEST(StronglyConnectedComponents, LargestFirstEachSorted) {
  const TopoMap map = build_or_fail(
      {node_at("a", 0, 0), node_at("b", 1, 0), node_at("c", 2, 0), node_at("d", 3, 0), node_at("e", 4, 0)},
      {edge("d", "e"), edge("e", "d"), edge("a", "c"), edge("c", "b"), edge("b", "a"), edge("c", "d")});
  const auto components = strongly_connected_components(map);
  ASSERT_EQ(components.size(), 2u);
  EXPECT_EQ(components[0], (std::vector<NodeIndex>{0, 1, 2}));
  EXPECT_EQ(components[1], (std::vector<NodeIndex>{3, 4}));
}

TEST(StronglyConnectedComponents, LongChainDoesNotOverflowTheStack) {
  // 200,000 nodes in one directed ring: a recursive algorithm would need 200,000 frames.
  constexpr int kNodes = 200000;
  std::vector<Node> nodes;
  std::vector<Edge> edges;
  for (int i = 0; i < kNodes; ++i) {
    nodes.push_back(node_at("n" + std::to_string(i), i, 0));
    edges.push_back(edge("n" + std::to_string(i), "n" + std::to_string((i + 1) % kNodes)));
  }
  const TopoMap map = build_or_fail(std::move(nodes), std::move(edges));
  EXPECT_EQ(strongly_connected_components(map).size(), 1u);
  EXPECT_TRUE(map_warnings(map).empty());
}

}  // namespace
}  // namespace rondo::map
