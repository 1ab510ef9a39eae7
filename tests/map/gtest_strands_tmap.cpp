// The STRANDS .tmap text importer.
#include <gtest/gtest.h>

#include <numbers>

#include "map_test_support.h"
#include "rondo/core/document.h"
#include "rondo/map/strands_import.h"

namespace rondo::map {
namespace {

using testing::fixture;

TEST(StrandsTmap, ReadsTheSmallFixture) {
  auto map = parse_strands_tmap(*read_text_file(fixture("small.tmap")), "maps/small.tmap");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->name(), "small");  // the file's stem
  ASSERT_EQ(map->node_count(), 4u);
  ASSERT_EQ(map->edge_count(), 6u);

  const Node& station = map->node(0);
  EXPECT_EQ(station.name, "Station");
  EXPECT_EQ(station.pose, (Pose{0, 0, 0}));
  EXPECT_EQ(station.influence, (std::vector<Point2>{{0.5, 0.5}, {-0.5, 0.5}, {-0.5, -0.5}}));
  EXPECT_DOUBLE_EQ(station.xy_goal_tolerance, kDefaultXyGoalTolerance);
  EXPECT_TRUE(station.meta.is_null());

  EXPECT_DOUBLE_EQ(map->node(1).pose.yaw, std::numbers::pi);       // quaternion (0,0,1,0)
  EXPECT_NEAR(map->node(2).pose.yaw, std::numbers::pi / 2, 1e-6);  // (0,0,.7071,.7071)
  EXPECT_TRUE(map->node(1).influence.empty());                     // empty vertices: section

  const Edge& dock = map->edge(0);
  EXPECT_EQ(dock.id, "Station_ChargingPoint");
  EXPECT_EQ(dock.action, "docking");
  EXPECT_FALSE(dock.top_speed.has_value());
  EXPECT_FALSE(dock.door.has_value());
  const Edge& into_office = map->edge(*map->find_edge("Hall_Office"));
  const Edge& out_of_office = map->edge(*map->find_edge("Office_Hall"));
  EXPECT_EQ(into_office.action, "doorPassing");
  EXPECT_EQ(into_office.door, "Hall_Office");
  EXPECT_EQ(out_of_office.door, "Hall_Office");  // both directions share the door
}

TEST(StrandsTmap, ToleratesLayoutQuirks) {
  // Windows line ends, spaces instead of tabs, name on the node: line, '+' signs, comments, blank lines.
  const std::string text =
      "# exported by hand\r\n\r\nnode: A\r\n  waypoint:\r\n    +1.0, 2.0 ,0,0,0,0,1\r\n  edges:\r\n"
      "    B,move_base\r\nnode:\r\n B\r\n waypoint:\r\n  0,0,0,0,0,0,1\r\n edges:\r\n  A, move_base\r\n";
  auto map = parse_strands_tmap(text, "quirks.tmap");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->node(0).name, "A");
  EXPECT_EQ(map->node(0).pose, (Pose{1.0, 2.0, 0.0}));
  EXPECT_EQ(map->edge(0).id, "A_B");
}

TEST(StrandsTmap, YawFromAnyFiniteQuaternion) {
  // Real files hold unnormalised and zero quaternions; a quaternion and its negation are one rotation.
  const double pi = std::numbers::pi;
  const std::vector<std::pair<std::string, double>> cases = {
      {"0,0,0,1", 0.0},
      {"0,0,1,0", pi},
      {"0,0,0.7071068,0.7071068", pi / 2},
      {"0,0,-0.7071068,0.7071068", -pi / 2},
      {"0,0,2,2", pi / 2},            // not of unit length
      {"0,0,1e300,1e300", pi / 2},    // would overflow unscaled
      {"0,0,1e-300,1e-300", pi / 2},  // would underflow to zero unscaled
      {"0,0,0.7071068,-0.7071068", -pi / 2},
      {"-0,-0,-0.7071068,-0.7071068", pi / 2},  // the negation of the third case
      {"0,0,0,0", 0.0},                         // the zero quaternion
      {"0.7071068,0,0,0.7071068", 0.0},         // pure roll
  };
  for (const auto& [quaternion, yaw] : cases) {
    const std::string text = "node:\n\tA\n\twaypoint:\n\t\t1,2,0," + quaternion + "\n";
    auto map = parse_strands_tmap(text, "q.tmap");
    ASSERT_TRUE(map.ok()) << quaternion << ": " << map.error().message;
    EXPECT_NEAR(map->node(0).pose.yaw, yaw, 1e-6) << quaternion;
  }
}

TEST(StrandsTmap, ParallelEdgesGetDistinctIds) {
  const std::string text =
      "node:\n\tA\n\twaypoint:\n\t\t0,0,0,0,0,0,1\n\tedges:\n\t\t B, move_base\n\t\t B, doorPassing\n"
      "node:\n\tB\n\twaypoint:\n\t\t1,0,0,0,0,0,1\n";
  auto map = parse_strands_tmap(text, "parallel.tmap");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->edge(0).id, "A_B");
  EXPECT_EQ(map->edge(1).id, "A_B_2");
}

struct BadTmap {
  const char* what;
  std::string text;
  std::string expected;
};

class StrandsTmapErrors : public ::testing::TestWithParam<BadTmap> {};

TEST_P(StrandsTmapErrors, NameFileLineAndProblem) {
  const BadTmap& c = GetParam();
  auto map = parse_strands_tmap(c.text, "bad.tmap");
  ASSERT_FALSE(map.ok()) << c.what;
  EXPECT_EQ(map.error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(map.error().message, c.expected) << c.what;
}

const std::string kNodeA = "node:\n\tA\n\twaypoint:\n\t\t0,0,0,0,0,0,1\n";

INSTANTIATE_TEST_SUITE_P(
    Malformed, StrandsTmapErrors,
    ::testing::Values(
        BadTmap{"empty", "", "bad.tmap: no 'node:' blocks: this is not a STRANDS .tmap map"},
        BadTmap{"garbage bytes", "\x89PNG\r\n\x1a\n\x00\x00", "bad.tmap:1: the text is not valid UTF-8"},
        // Fuzzing found this: a Latin-1 name imported fine but wrote a rondo file that could not be read back.
        BadTmap{"name not UTF-8", "node:\n\tCaf\xe9\n\twaypoint:\n\t\t0,0,0,0,0,0,1\n",
                "bad.tmap:2: the text is not valid UTF-8"},
        BadTmap{"text before the first node", "hello\n" + kNodeA,
                "bad.tmap:1: expected 'node:' to start the first node, found 'hello'"},
        BadTmap{"truncated after node:", kNodeA + "node:\n", "bad.tmap:5: 'node:' is not followed by the node's name"},
        BadTmap{"truncated before the waypoint", kNodeA + "node:\n\tB\n\twaypoint:\n",
                "bad.tmap:5: node 'B' has no 'waypoint:' line (x,y,z,qx,qy,qz,qw)"},
        BadTmap{"short waypoint", "node:\n\tA\n\twaypoint:\n\t\t1,2,3\n",
                "bad.tmap:4: a waypoint is 7 numbers x,y,z,qx,qy,qz,qw; found 3 fields in '1,2,3'"},
        BadTmap{"word in waypoint", "node:\n\tA\n\twaypoint:\n\t\t1,two,0,0,0,0,1\n",
                "bad.tmap:4: waypoint field 2 of node 'A' is not a finite number: 'two'"},
        BadTmap{"NaN in waypoint", "node:\n\tA\n\twaypoint:\n\t\tnan,0,0,0,0,0,1\n",
                "bad.tmap:4: waypoint field 1 of node 'A' is not a finite number: 'nan'"},
        BadTmap{"second waypoint", kNodeA + "\t\t1,1,0,0,0,0,1\n",
                "bad.tmap:5: node 'A' has a second waypoint line '1,1,0,0,0,0,1'"},
        BadTmap{"unknown section", kNodeA + "\tcolour:\n",
                "bad.tmap:5: unknown section 'colour:' (expected waypoint:, edges: or vertices:)"},
        BadTmap{"line outside a section", "node:\n\tA\n\tstray\n",
                "bad.tmap:3: expected 'waypoint:', 'edges:' or 'vertices:' in node 'A', found 'stray'"},
        BadTmap{"edge without action", kNodeA + "\tedges:\n\t\t B\n",
                "bad.tmap:6: an edge line is 'target, action', found 'B'"},
        BadTmap{"vertex with three numbers", kNodeA + "\tvertices:\n\t\t1,2,3\n",
                "bad.tmap:6: a vertex is 'x,y', found '1,2,3'"},
        BadTmap{"vertex word", kNodeA + "\tvertices:\n\t\t1,y\n",
                "bad.tmap:6: a vertex is two finite numbers 'x,y', found '1,y'"},
        BadTmap{"unknown target", kNodeA + "\tedges:\n\t\t Lab, move_base\n",
                "bad.tmap:6: edges[0] 'A_Lab': to: no node named 'Lab'"},
        BadTmap{
            "self-loop", kNodeA + "\tedges:\n\t\t A, move_base\n",
            "bad.tmap:6: edges[0] 'A_A': to: the edge leads from node 'A' back to itself (self-loops are not allowed)"},
        BadTmap{"duplicate node", kNodeA + kNodeA,
                "bad.tmap:5: nodes[1] 'A': name: node 'A' is already defined by nodes[0]"},
        BadTmap{"second waypoint section", kNodeA + "\twaypoint:\n",
                "bad.tmap:5: node 'A' has a second 'waypoint:' section"}));

}  // namespace
}  // namespace rondo::map
