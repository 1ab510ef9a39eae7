// The STRANDS YAML and JSON importers.
#include <gtest/gtest.h>

#include <numbers>

#include "map_test_support.h"
#include "rondo/core/document.h"
#include "rondo/map/strands_import.h"

namespace rondo::map {
namespace {

using testing::fixture;

void expect_small_strands_map(const TopoMap& map) {
  EXPECT_EQ(map.name(), "lab_small");  // the pointset
  ASSERT_EQ(map.node_count(), 3u);
  ASSERT_EQ(map.edge_count(), 4u);

  const Node& hall = map.node(0);
  EXPECT_EQ(hall.name, "Hall");
  EXPECT_EQ(hall.pose, (Pose{0, 0, 0}));
  EXPECT_EQ(hall.influence, (std::vector<Point2>{{0.5, 0.5}, {-0.5, 0.5}, {0.0, -0.5}}));
  // meta keeps what is not bookkeeping
  EXPECT_EQ(hall.meta, (Json{{"contains", Json::array({Json{{"category", "office"}, {"name", "L-101"}}})}}));

  const Node& office = map.node(1);
  EXPECT_NEAR(office.pose.yaw, std::numbers::pi / 2, 1e-6);
  EXPECT_DOUBLE_EQ(office.xy_goal_tolerance, 0.5);
  EXPECT_DOUBLE_EQ(office.yaw_goal_tolerance, 6.28);
  EXPECT_TRUE(office.influence.empty());
  EXPECT_TRUE(office.meta.is_null());

  const Node& lab = map.node(2);
  EXPECT_EQ(lab.pose, (Pose{-3, 0, 0}));  // zero quaternion: yaw 0
  EXPECT_DOUBLE_EQ(lab.xy_goal_tolerance, kDefaultXyGoalTolerance);
  EXPECT_TRUE(lab.meta.is_null());  // empty localise_by_topic is dropped

  EXPECT_EQ(map.edge(0).id, "Hall_Office");
  EXPECT_EQ(map.edge(0).top_speed, 0.55);
  EXPECT_FALSE(map.edge(0).door.has_value());
  EXPECT_EQ(map.edge(1).action, "door_wait_and_pass");
  EXPECT_EQ(map.edge(1).door, "Hall_Lab");
  EXPECT_EQ(map.edge(2).id, "Office_Hall");  // no edge_id in the file
  EXPECT_FALSE(map.edge(2).top_speed.has_value());
  EXPECT_EQ(map.edge(3).id, "Lab_Hall");
  EXPECT_EQ(map.edge(3).door, "Hall_Lab");
}

TEST(StrandsYaml, ReadsTheSmallFixture) {
  auto map = parse_strands_yaml(*read_text_file(fixture("small_strands.yaml")), "small_strands.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  expect_small_strands_map(*map);
}

TEST(StrandsJson, ReadsTheSmallFixture) {
  auto map = parse_strands_json(*read_text_file(fixture("small_strands.json")), "small_strands.json");
  ASSERT_TRUE(map.ok()) << map.error().message;
  expect_small_strands_map(*map);
}

TEST(StrandsYaml, AcceptsOlderShapes) {
  // A bare node (no {meta, node} wrapper), an integer name, a name only in meta, no orientation,
  // edges: null, a non-empty localise_by_topic kept as meta, no pointset (no name).
  const std::string text = R"(
- name: 12
  pose: {position: {x: 1, y: 2}}
  edges: [{node: B, action: move_base}]
- meta: {node: B}
  node:
    pose: {position: {x: 0, y: 0}, orientation: {z: 1}}
    edges: null
    localise_by_topic: '{"topic": "battery_state"}'
)";
  auto map = parse_strands_yaml(text, "old.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->name(), "");
  EXPECT_EQ(map->node(0).name, "12");
  EXPECT_EQ(map->node(0).pose, (Pose{1, 2, 0}));
  EXPECT_EQ(map->node(1).name, "B");
  EXPECT_DOUBLE_EQ(map->node(1).pose.yaw, std::numbers::pi);
  EXPECT_EQ(map->node(1).meta, (Json{{"localise_by_topic", "{\"topic\": \"battery_state\"}"}}));
  EXPECT_EQ(map->edge(0).id, "12_B");
}

TEST(StrandsYaml, DefaultIdsAvoidIdsTheFileGives) {
  const std::string text = R"(
- node:
    name: A
    pose: {position: {x: 0, y: 0}}
    edges: [{node: B, action: move_base}, {node: B, action: doorPassing, edge_id: A_B}]
- node:
    name: B
    pose: {position: {x: 1, y: 0}}
)";
  auto map = parse_strands_yaml(text, "ids.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->edge(0).id, "A_B_2");
  EXPECT_EQ(map->edge(1).id, "A_B");
}

struct BadStrands {
  const char* what;
  bool json;
  std::string text;
  std::string expected;
};

class StrandsErrors : public ::testing::TestWithParam<BadStrands> {};

TEST_P(StrandsErrors, NameFileLineFieldAndProblem) {
  const BadStrands& c = GetParam();
  auto map = c.json ? parse_strands_json(c.text, "bad.json") : parse_strands_yaml(c.text, "bad.yaml");
  ASSERT_FALSE(map.ok()) << c.what;
  EXPECT_EQ(map.error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(map.error().message, c.expected) << c.what;
}

const std::string kNodeB = "- node:\n    name: B\n    pose: {position: {x: 1, y: 0}}\n";

INSTANTIATE_TEST_SUITE_P(
    Malformed, StrandsErrors,
    ::testing::Values(
        BadStrands{"truncated YAML", false, "- meta: {node: A}\n  node:\n    name: A\n    pose: {position: {x: 0,",
                   "bad.yaml:4: end of map flow not found"},
        BadStrands{"truncated JSON", true, "[{\"node\": {\"name\": \"A\", \"pose\": ",
                   "bad.json: [json.exception.parse_error.101] parse error at line 1, column 33: syntax error while "
                   "parsing value - unexpected end of input; expected '[', '{', or a literal"},
        BadStrands{"garbage bytes", false, "\xff\xd8\xff\xe0 JFIF", "bad.yaml:1: the text is not valid UTF-8"},
        BadStrands{"empty list", false, "[]\n", "bad.yaml:1: the map has no nodes"},
        BadStrands{"scalar root", true, "42",
                   "bad.json: expected a STRANDS topological map: a list of entries with 'meta' and 'node'"},
        BadStrands{"entry is a list", false, "- [1, 2]\n",
                   "bad.yaml:1: [0]: expected a map entry: a mapping with 'meta' and 'node'"},
        BadStrands{"entry without node", false, "- meta: {node: A}\n",
                   "bad.yaml:1: [0]: expected a map entry with a 'node' mapping (or a node with 'name' and 'pose')"},
        BadStrands{"missing name", false, "- node:\n    pose: {position: {x: 0, y: 0}}\n",
                   "bad.yaml:2: [0].node: missing field 'name'"},
        BadStrands{"missing pose", false, "- node: {name: A}\n", "bad.yaml:1: [0].node: missing field 'pose'"},
        BadStrands{"missing position y", false, "- node:\n    name: A\n    pose: {position: {x: 0}}\n",
                   "bad.yaml:3: [0].node.pose.position: missing field 'y'"},
        BadStrands{"wrong type", true, R"([{"node": {"name": "A", "pose": {"position": {"x": "0", "y": 0}}}}])",
                   "bad.json: [0].node.pose.position.x: expected a number, found text"},
        BadStrands{"quaternion not a mapping", false,
                   "- node:\n    name: A\n    pose: {position: {x: 0, y: 0}, orientation: 1}\n",
                   "bad.yaml:3: [0].node.pose.orientation: expected a quaternion mapping with x, y, z, w"},
        BadStrands{"name is a list", false, "- node:\n    name: [A]\n    pose: {position: {x: 0, y: 0}}\n",
                   "bad.yaml:2: [0].node.name: expected text, found a list"},
        BadStrands{"edges not a list", false,
                   "- node:\n    name: A\n    pose: {position: {x: 0, y: 0}}\n    edges: B\n",
                   "bad.yaml:4: [0].node.edges: expected a list"},
        BadStrands{"edge without target", false,
                   "- node:\n    name: A\n    pose: {position: {x: 0, y: 0}}\n    edges:\n    - {action: move_base}\n",
                   "bad.yaml:5: [0].node.edges[0]: missing field 'node'"},
        BadStrands{
            "unknown node reference", false,
            "- node:\n    name: A\n    pose: {position: {x: 0, y: 0}}\n    edges:\n    - {node: B, action: move_base}\n"
            "    - {node: Lab, action: move_base}\n" +
                kNodeB,
            "bad.yaml:6: [0].node.edges[1].node: edge 'A_Lab': no node named 'Lab'"},
        BadStrands{"negative top_vel", false,
                   "- node:\n    name: A\n    pose: {position: {x: 0, y: 0}}\n    edges:\n    - {node: B, action: "
                   "move_base, top_vel: -1}\n" +
                       kNodeB,
                   "bad.yaml:5: [0].node.edges[0].top_vel: edge 'A_B': must be a finite speed above 0 m/s, not -1"},
        BadStrands{
            "self-loop", true,
            R"([{"node": {"name": "A", "pose": {"position": {"x": 0, "y": 0}}, "edges": [{"node": "A", "action": "move_base"}]}}])",
            "bad.json: [0].node.edges[0].node: edge 'A_A': the edge leads from node 'A' back to itself (self-loops are "
            "not allowed)"},
        BadStrands{"duplicate node", false, kNodeB + kNodeB,
                   "bad.yaml:5: [1].node.name: node 'B' is already defined by nodes[0]"},
        BadStrands{
            "duplicate edge id", false,
            "- node:\n    name: A\n    pose: {position: {x: 0, y: 0}}\n    edges:\n    - {node: B, edge_id: e1}\n"
            "    - {node: B, edge_id: e1}\n" +
                kNodeB,
            "bad.yaml:6: [0].node.edges[1].edge_id: edge 'e1': edge id 'e1' is already used by edges[0]"},
        BadStrands{"negative tolerance", false,
                   "- node:\n    name: A\n    pose: {position: {x: 0, y: 0}}\n    yaw_goal_tolerance: -0.1\n",
                   "bad.yaml:4: [0].node.yaw_goal_tolerance: must be a finite number of radians, 0 or more"},
        BadStrands{"vertex without y", false,
                   "- node:\n    name: A\n    pose: {position: {x: 0, y: 0}}\n    verts: [{x: 1}]\n",
                   "bad.yaml:4: [0].node.verts[0]: missing field 'y'"}));

TEST(DoorId, IsTheSameInBothDirections) {
  EXPECT_EQ(door_id_between("WayPoint2", "WayPoint14"), "WayPoint14_WayPoint2");
  EXPECT_EQ(door_id_between("WayPoint14", "WayPoint2"), "WayPoint14_WayPoint2");
}

}  // namespace
}  // namespace rondo::map
