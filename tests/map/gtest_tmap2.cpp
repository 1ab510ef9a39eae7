// The tmap2 importer (LCAS topological_navigation): the real files of tests/data/maps/lcas_*,
// detection by content, anchors and aliases, restrictions, and malformed variants.
#include <gtest/gtest.h>

#include <cctype>
#include <fstream>
#include <numbers>

#include "map_test_support.h"
#include "rondo/core/document.h"
#include "rondo/map/map_loader.h"
#include "rondo/map/map_yaml.h"
#include "rondo/map/tmap2_import.h"

namespace rondo::map {
namespace {

using testing::fixture;
using testing::TempDir;

Result<Tmap2Import> load_fixture(const std::string& name) {
  auto text = read_text_file(fixture(name));
  if (!text) return text.error();
  return parse_tmap2(*text, name);
}

void write_file(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
}

// The expected values were read from the same files with PyYAML (yaw = atan2 of the quaternion).
struct RealTmap2 {
  std::string file;
  std::string name;
  std::size_t nodes;
  std::size_t edges;
  Node last_node;  // name, pose, tolerances; influence checked by size and first vertex
  std::size_t last_verts;
  Point2 last_first_vertex;
  Edge last_edge;
  std::size_t warnings;
};

Node node_with(std::string name, Pose pose, double xy, double yaw) {
  Node n;
  n.name = std::move(name);
  n.pose = pose;
  n.xy_goal_tolerance = xy;
  n.yaw_goal_tolerance = yaw;
  return n;
}

Edge edge_with(std::string id, std::string from, std::string to, std::string action,
               std::optional<double> top_speed = std::nullopt) {
  return Edge{.id = std::move(id),
              .from = std::move(from),
              .to = std::move(to),
              .action = std::move(action),
              .top_speed = top_speed,
              .door = std::nullopt};
}

class RealTmap2Files : public ::testing::TestWithParam<RealTmap2> {};

TEST_P(RealTmap2Files, ImportWithTheirNodesEdgesAndPoses) {
  const RealTmap2& c = GetParam();
  auto in = load_fixture(c.file);
  ASSERT_TRUE(in.ok()) << in.error().message;
  const TopoMap& map = in->map;
  EXPECT_EQ(map.name(), c.name);
  ASSERT_EQ(map.node_count(), c.nodes);
  ASSERT_EQ(map.edge_count(), c.edges);
  const Node& last = map.nodes().back();
  EXPECT_EQ(last.name, c.last_node.name);
  EXPECT_DOUBLE_EQ(last.pose.x, c.last_node.pose.x);
  EXPECT_DOUBLE_EQ(last.pose.y, c.last_node.pose.y);
  EXPECT_NEAR(last.pose.yaw, c.last_node.pose.yaw, 1e-12);
  EXPECT_DOUBLE_EQ(last.xy_goal_tolerance, c.last_node.xy_goal_tolerance);
  EXPECT_DOUBLE_EQ(last.yaw_goal_tolerance, c.last_node.yaw_goal_tolerance);
  ASSERT_EQ(last.influence.size(), c.last_verts);
  EXPECT_EQ(last.influence.front(), c.last_first_vertex);
  EXPECT_EQ(map.edges().back(), c.last_edge);
  EXPECT_EQ(in->warnings.size(), c.warnings);
  // Every edge keeps the id the file gives it, "<from>_<to>" in all of these files.
  for (const Edge& e : map.edges()) EXPECT_EQ(e.id, e.from + "_" + e.to);
  // Rondo's format holds everything that was imported.
  auto again = parse_map_yaml(write_map_yaml(map), "again.yaml");
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(*again, map);
}

INSTANTIATE_TEST_SUITE_P(Lcas, RealTmap2Files,
                         ::testing::Values(
                             // tests/conf/test.tmap2: ROS 2 form, NavigateToPose, `config: &id001 []` and `*id001`.
                             RealTmap2{"lcas_tests_conf_test.tmap2",
                                       "new_map",
                                       2,
                                       2,
                                       node_with("WayPoint2", {10, 10, 0}, 0.3, 0.1),
                                       8,
                                       {0.692909649383465, 0.2870125742738173},
                                       edge_with("WayPoint2_WayPoint1", "WayPoint2", "WayPoint1", "NavigateToPose"),
                                       0},
                             // maps/test.tmap2 (2022): the goal is the anchored part, `goal: &id001`.
                             RealTmap2{"lcas_maps_test.tmap2",
                                       "test",
                                       6,
                                       12,
                                       node_with("WayPoint5", {7.5, 2.5, 0}, 0.3, 0.2),
                                       8,
                                       {0.689999997616, 0.287000000477},
                                       edge_with("WayPoint5_WayPoint2", "WayPoint5", "WayPoint2", "move_base"),
                                       0},
                             // maps/test.tmap2 (2021): top_vel in a `config` mapping, `restrictions` mappings.
                             RealTmap2{"lcas_maps_test_2021.tmap2",
                                       "new_map",
                                       4,
                                       8,
                                       node_with("D", {3, 1, 0}, 0.3, 0.1),
                                       8,
                                       {0.692909649383465, 0.2870125742738173},
                                       edge_with("D_C", "D", "C", "move_base", 0.55),
                                       0},
                             // A real site: node restrictions on both sides of each row, policy actions, turned poses.
                             RealTmap2{"lcas_certh_vogui_2sides_policies.tmap2",
                                       "tmap_certh1",
                                       24,
                                       52,
                                       node_with("c1_sb", {-5.407455410218223, -6.258307241342934, 2.1599292755126953},
                                                 0.3, 0.3),
                                       8,
                                       {0.34645482469465, 0.143506287138173},
                                       edge_with("c1_sb_c0_sb", "c1_sb", "c0_sb", "row_change/move_base"),
                                       2}));

TEST(Tmap2, KeepsMetaLocalisationAndNodeRestrictions) {
  auto in = load_fixture("lcas_certh_vogui_2sides_policies.tmap2");
  ASSERT_TRUE(in.ok()) << in.error().message;
  const TopoMap& map = in->map;
  // The bookkeeping keys of meta (map, node, pointset) are dropped; restrictions other than
  // 'True' are kept.
  EXPECT_EQ(map.node(*map.find_node("c0_p0_a")).meta, (Json{{"restrictions_planning", "allowedside_a"}}));
  EXPECT_EQ(map.node(*map.find_node("c0_p0_b")).meta, (Json{{"restrictions_planning", "~allowedside_a"}}));
  EXPECT_NEAR(map.node(0).pose.yaw, -0.9791372418403627, 1e-12);
  EXPECT_EQ(map.edge(*map.find_edge("c0_p0_b_c0_sa")).action, "nav_policy_goal");
  ASSERT_EQ(in->warnings.size(), 2u);
  EXPECT_EQ(in->warnings[0],
            "restrictions_planning 'allowedside_a' on 10 nodes (the first 'c0_p0_a') is kept in the node's meta but "
            "not applied: rondo plans as if open to every robot");
  EXPECT_EQ(in->warnings[1].rfind("restrictions_planning '~allowedside_a' on 10 nodes (the first 'c0_p0_b')", 0), 0u)
      << in->warnings[1];
  // The 2021 form: empty `restrictions` mappings restrict nothing, so nothing is kept or said.
  auto old = load_fixture("lcas_maps_test_2021.tmap2");
  ASSERT_TRUE(old.ok()) << old.error().message;
  for (const Node& n : old->map.nodes()) EXPECT_TRUE(n.meta.is_null()) << n.name;
}

// A small tmap2 map in the shape of the real files, written here so that each malformed variant
// below changes one thing. Line numbers matter: the variants keep them.
const std::string kBase = R"(meta: {last_updated: 2024-01-01_00-00-00}
metric_map: map_2d
name: lab
pointset: lab
nodes:
- meta: {map: map_2d, node: A, pointset: lab, tag: [charging]}
  node:
    name: A
    pose:
      position: {x: 0.0, y: 0.0, z: 0.0}
      orientation: {x: 0.0, y: 0.0, z: 0.7071067811865476, w: 0.7071067811865476}
    properties: {xy_goal_tolerance: 0.25, yaw_goal_tolerance: 0.2}
    verts: [{x: 0.5, y: 0.5}, {x: -0.5, y: 0.5}, {x: 0.0, y: -0.5}]
    localise_by_topic: ''
    edges:
    - {edge_id: A_B, node: B, action: move_base, config: [], fail_policy: fail, restrictions_planning: 'True'}
- meta: {map: map_2d, node: B, pointset: lab}
  node:
    name: B
    pose:
      position: {x: 2.0, y: 0.0, z: 0.0}
      orientation: {x: 0.0, y: 0.0, z: 0.0, w: 1.0}
    properties: {xy_goal_tolerance: 0.3, yaw_goal_tolerance: 0.1}
    edges:
    - {edge_id: B_A, node: A, action: door_wait_and_move, top_vel: 0.3}
)";

// kBase with the first occurrence of `from` replaced by `to`.
std::string variant(const std::string& from, const std::string& to) {
  std::string text = kBase;
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST(Tmap2, ReadsEveryFieldOfTheBaseMap) {
  auto in = parse_tmap2(kBase, "t.tmap2");
  ASSERT_TRUE(in.ok()) << in.error().message;
  const TopoMap& map = in->map;
  EXPECT_EQ(map.name(), "lab");
  const Node& a = map.node(0);
  EXPECT_EQ(a.pose.x, 0.0);
  EXPECT_NEAR(a.pose.yaw, std::numbers::pi / 2, 1e-12);
  EXPECT_EQ(a.xy_goal_tolerance, 0.25);
  EXPECT_EQ(a.yaw_goal_tolerance, 0.2);
  EXPECT_EQ(a.influence, (std::vector<Point2>{{0.5, 0.5}, {-0.5, 0.5}, {0.0, -0.5}}));
  EXPECT_EQ(a.meta, (Json{{"tag", Json::array({"charging"})}}));
  EXPECT_TRUE(map.node(1).meta.is_null());
  EXPECT_EQ(map.edge(0), edge_with("A_B", "A", "B", "move_base"));
  // A door action gets the door id both directions share, as for STRANDS maps.
  Edge door = edge_with("B_A", "B", "A", "door_wait_and_move", 0.3);
  door.door = "A_B";
  EXPECT_EQ(map.edge(1), door);
  EXPECT_TRUE(in->warnings.empty());
}

TEST(Tmap2, AnchorsAndAliasesReadAsTheirValues) {
  // PyYAML writes repeated parts once, as &id001 and *id001; any part may be shared.
  const std::string text = R"(meta: {last_updated: x}
name: shared
nodes:
- meta: {map: m, node: A, pointset: shared}
  node:
    name: A
    pose: &pose
      position: {x: 1.5, y: -2.0, z: 0.0}
      orientation: &q {x: 0.0, y: 0.0, z: 1.0, w: 0.0}
    properties: &props {xy_goal_tolerance: 0.4, yaw_goal_tolerance: 6.28}
    verts: &verts [{x: 1, y: 0}, {x: 0, y: 1}, {x: -1, y: 0}]
    edges:
    - {edge_id: A_B, node: B, action: &act row_traversal, config: &id001 [], goal: &goal {pose: $node.pose}}
- meta: {map: m, node: B, pointset: shared}
  node:
    name: B
    pose: {position: {x: 0.0, y: 0.0}, orientation: *q}
    properties: *props
    verts: *verts
    edges:
    - {edge_id: B_A, node: A, action: *act, config: *id001, goal: *goal}
)";
  auto in = parse_tmap2(text, "alias.tmap2");
  ASSERT_TRUE(in.ok()) << in.error().message;
  const TopoMap& map = in->map;
  EXPECT_EQ(map.node(0).pose.x, 1.5);
  EXPECT_NEAR(map.node(1).pose.yaw, std::numbers::pi, 1e-12);
  EXPECT_EQ(map.node(1).xy_goal_tolerance, 0.4);
  EXPECT_EQ(map.node(1).yaw_goal_tolerance, 6.28);
  EXPECT_EQ(map.node(1).influence, map.node(0).influence);
  EXPECT_EQ(map.edge(1).action, "row_traversal");
}

TEST(Tmap2, EdgeRestrictionsAreWarnedAboutGroupedByExpression) {
  std::string text = variant("restrictions_planning: 'True'}", "restrictions_planning: robot_short}");
  const std::string old = "action: door_wait_and_move, top_vel: 0.3}";
  text.replace(text.find(old), old.size(),
               "action: move_base, restrictions_planning: robot_short, restrictions: {robot_type: tall}}");
  auto in = parse_tmap2(text, "r.tmap2");
  ASSERT_TRUE(in.ok()) << in.error().message;
  EXPECT_EQ(in->warnings,
            (std::vector<std::string>{
                "restrictions_planning 'robot_short' on 2 edges (the first 'A_B') is not applied: rondo plans as if "
                "open to every robot",
                "restrictions '{\"robot_type\":\"tall\"}' on 1 edge (the first 'B_A') is not applied: rondo plans as "
                "if open to every robot"}));
}

TEST(Tmap2, ManyKindsOfRestrictionAreCountedNotListed) {
  std::string text = "meta: {}\nnodes:\n";
  for (int i = 0; i < 14; ++i) {
    const std::string n = std::to_string(i);
    text += "- node: {name: N" + n + ", pose: {position: {x: " + n + ", y: 0}}, restrictions_runtime: r" + n + "}\n";
  }
  auto in = parse_tmap2(text, "many.tmap2");
  ASSERT_TRUE(in.ok()) << in.error().message;
  ASSERT_EQ(in->warnings.size(), 11u);
  EXPECT_EQ(in->warnings.back(), "and 4 more kinds of restriction, not applied either");
}

TEST(Tmap2, DetectedByContentWhateverTheFileName) {
  TempDir dir;
  const std::string real = *read_text_file(fixture("lcas_maps_test.tmap2"));
  for (const char* name : {"m.tmap2", "m.yaml", "m.yml", "m.tmap2.yaml"}) {
    write_file(dir.path() / name, real);
    auto loaded = load_map_file(dir.path() / name);
    ASSERT_TRUE(loaded.ok()) << name << ": " << loaded.error().message;
    EXPECT_EQ(loaded->format, MapFormat::kTmap2) << name;
    EXPECT_EQ(loaded->map.node_count(), 6u) << name;
  }
  // Without the top-level tmap2 keys, the {meta, node} entries of `nodes` still say tmap2.
  write_file(dir.path() / "bare.yaml", "nodes:\n- node: {name: A, pose: {position: {x: 0, y: 0}}, edges: []}\n");
  auto bare = load_map_file(dir.path() / "bare.yaml");
  ASSERT_TRUE(bare.ok()) << bare.error().message;
  EXPECT_EQ(bare->format, MapFormat::kTmap2);
  // And the other formats under a .tmap2 name are read as what they are.
  write_file(dir.path() / "rondo.tmap2", *read_text_file(fixture("office.yaml")));
  write_file(dir.path() / "strands.tmap2", *read_text_file(fixture("small_strands.yaml")));
  EXPECT_EQ(load_map_file(dir.path() / "rondo.tmap2")->format, MapFormat::kRondo);
  EXPECT_EQ(load_map_file(dir.path() / "strands.tmap2")->format, MapFormat::kStrandsYaml);
  // A .tmap2 file that is none of them is told what a tmap2 map needs.
  write_file(dir.path() / "scalar.tmap2", "42\n");
  write_file(dir.path() / "empty_mapping.tmap2", "name: site\n");
  EXPECT_NE(load_map_file(dir.path() / "scalar.tmap2").error().message.find(":1: expected a tmap2 map"),
            std::string::npos);
  EXPECT_NE(load_map_file(dir.path() / "empty_mapping.tmap2").error().message.find(":1: missing field 'nodes'"),
            std::string::npos);
}

TEST(Tmap2, DetectionNeverTakesRondoOrStrandsDocuments) {
  for (const char* file : {"office.yaml", "small.yaml", "small_strands.yaml"}) {
    auto doc = Document::parse(*read_text_file(fixture(file)), DocumentFormat::kYaml, file);
    ASSERT_TRUE(doc.ok());
    EXPECT_FALSE(is_tmap2_document(*doc)) << file;
  }
  auto doc = Document::parse(kBase, DocumentFormat::kYaml, "t.tmap2");
  ASSERT_TRUE(doc.ok());
  EXPECT_TRUE(is_tmap2_document(*doc));
  // A rondo map with a stray tmap2 key stays rondo's, and hears about the key.
  TempDir dir;
  std::ofstream(dir.path() / "stray.yaml") << "meta: {}\nnodes:\n  - {name: A, pose: {x: 0, y: 0}}\n";
  auto stray = load_map_file(dir.path() / "stray.yaml");
  ASSERT_FALSE(stray.ok());
  EXPECT_NE(stray.error().message.find(":1: meta: unknown field 'meta'"), std::string::npos) << stray.error().message;
  // An empty or missing node list leaves only the top-level keys to judge by.
  for (const char* text : {"meta: {}\nnodes: []\n", "pointset: p\n", "transformation: {}\nnodes: 3\n"}) {
    auto d = Document::parse(text, DocumentFormat::kYaml, "t.yaml");
    ASSERT_TRUE(d.ok());
    EXPECT_TRUE(is_tmap2_document(*d)) << text;
  }
  auto not_tmap2 = parse_tmap2("- node: {name: A, pose: {position: {x: 0, y: 0}}}\n", "list.tmap2");
  ASSERT_FALSE(not_tmap2.ok());
  EXPECT_EQ(not_tmap2.error().message,
            "list.tmap2:1: expected a tmap2 map: a mapping with 'meta', 'name', 'pointset' and 'nodes'");
}

struct BadTmap2 {
  const char* what;
  std::string text;
  std::string expected;  // the whole message
};

class Tmap2Errors : public ::testing::TestWithParam<BadTmap2> {};

TEST_P(Tmap2Errors, NameFileLineFieldAndProblem) {
  const BadTmap2& c = GetParam();
  auto in = parse_tmap2(c.text, "t.tmap2");
  ASSERT_FALSE(in.ok()) << c.what;
  EXPECT_EQ(in.error().code, ErrorCode::kInvalidInput) << c.what;
  EXPECT_EQ(in.error().message, c.expected) << c.what;
}

INSTANTIATE_TEST_SUITE_P(
    Malformed, Tmap2Errors,
    ::testing::Values(
        BadTmap2{"missing name", variant("    name: B\n", "    label: B\n"),
                 "t.tmap2:19: nodes[1].node: missing field 'name'"},
        BadTmap2{"name is a list", variant("    name: B\n", "    name: [B]\n"),
                 "t.tmap2:19: nodes[1].node.name: expected text, found a list"},
        BadTmap2{"edge to an unknown node", variant("node: B, action", "node: Lab, action"),
                 "t.tmap2:16: nodes[0].node.edges[0].node: edge 'A_B': no node named 'Lab'"},
        BadTmap2{"position x is text", variant("{x: 2.0, y: 0.0", "{x: two, y: 0.0"),
                 "t.tmap2:21: nodes[1].node.pose.position.x: expected a number, found text"},
        BadTmap2{"position without y", variant("{x: 2.0, y: 0.0, z: 0.0}", "{x: 2.0, z: 0.0}"),
                 "t.tmap2:21: nodes[1].node.pose.position: missing field 'y'"},
        BadTmap2{"pose without position", variant("      position: {x: 2.0, y: 0.0, z: 0.0}\n", "      where: 1\n"),
                 "t.tmap2:21: nodes[1].node.pose: missing field 'position'"},
        BadTmap2{"pose missing", variant("    pose:\n      position: {x: 0.0", "    place:\n      position: {x: 0.0"),
                 "t.tmap2:8: nodes[0].node: missing field 'pose'"},
        BadTmap2{"quaternion is a number", variant("orientation: {x: 0.0, y: 0.0, z: 0.0, w: 1.0}", "orientation: 1"),
                 "t.tmap2:22: nodes[1].node.pose.orientation: expected a quaternion mapping with x, y, z, w"},
        BadTmap2{"quaternion component is text", variant("w: 1.0}", "w: one}"),
                 "t.tmap2:22: nodes[1].node.pose.orientation.w: expected a number, found text"},
        BadTmap2{"properties is a number",
                 variant("properties: {xy_goal_tolerance: 0.3, yaw_goal_tolerance: 0.1}", "properties: 0.3"),
                 "t.tmap2:23: nodes[1].node.properties: expected a mapping with the goal tolerances"},
        BadTmap2{"negative tolerance", variant("xy_goal_tolerance: 0.25", "xy_goal_tolerance: -0.25"),
                 "t.tmap2:12: nodes[0].node.properties.xy_goal_tolerance: must be a finite number of metres, 0 or "
                 "more"},
        BadTmap2{"vertex without y", variant("{x: 0.0, y: -0.5}", "{x: 0.0}"),
                 "t.tmap2:13: nodes[0].node.verts[2]: missing field 'y'"},
        BadTmap2{"entry without node", variant("  node:\n    name: B", "  nodo:\n    name: B"),
                 "t.tmap2:17: nodes[1]: missing field 'node'"},
        BadTmap2{"node is text", "meta: {}\nnodes:\n- {meta: {}, node: A}\n",
                 "t.tmap2:3: nodes[0].node: expected a mapping with 'name', 'pose' and 'edges'"},
        BadTmap2{"entry is a list", "meta: {}\nnodes:\n- [A]\n",
                 "t.tmap2:3: nodes[0]: expected a tmap2 node entry: a mapping with 'meta' and 'node'"},
        BadTmap2{"nodes is a mapping", "meta: {}\nname: x\nnodes: {A: 1}\n", "t.tmap2:3: nodes: expected a list"},
        BadTmap2{"no nodes", "meta: {}\nname: x\nnodes: []\n", "t.tmap2:3: nodes: the map has no nodes"},
        BadTmap2{"nodes missing", "meta: {}\nname: x\n", "t.tmap2:1: missing field 'nodes'"},
        BadTmap2{"map name is a list", variant("name: lab\n", "name: [lab]\n"),
                 "t.tmap2:3: name: expected text, found a list"},
        BadTmap2{"edges is text",
                 variant("    edges:\n    - {edge_id: B_A, node: A, action: door_wait_and_move, top_vel: 0.3}\n",
                         "    edges: B_A\n"),
                 "t.tmap2:24: nodes[1].node.edges: expected a list"},
        BadTmap2{"broken YAML", variant("    edges:\n    - {edge_id: B_A", "    edges: none\n    - {edge_id: B_A"),
                 "t.tmap2:25: end of map not found"},
        BadTmap2{"edge without target", variant("{edge_id: B_A, node: A, ", "{edge_id: B_A, "),
                 "t.tmap2:25: nodes[1].node.edges[0]: missing field 'node'"},
        BadTmap2{"edge is text",
                 variant("    - {edge_id: B_A, node: A, action: door_wait_and_move, top_vel: 0.3}", "    - B_A"),
                 "t.tmap2:25: nodes[1].node.edges[0]: expected an edge: a mapping with 'edge_id', 'node' and "
                 "'action'"},
        BadTmap2{"action is a list", variant("action: door_wait_and_move", "action: [door]"),
                 "t.tmap2:25: nodes[1].node.edges[0].action: expected text, found a list"},
        BadTmap2{"empty edge id", variant("edge_id: B_A", "edge_id: ''"),
                 "t.tmap2:25: nodes[1].node.edges[0].edge_id: an edge id must not be empty"},
        BadTmap2{"duplicate edge id", variant("edge_id: B_A", "edge_id: A_B"),
                 "t.tmap2:25: nodes[1].node.edges[0].edge_id: edge 'A_B': edge id 'A_B' is already used by edges[0]"},
        BadTmap2{"duplicate node", variant("    name: B\n", "    name: A\n"),
                 "t.tmap2:19: nodes[1].node.name: node 'A' is already defined by nodes[0] (and 2 more problems)"},
        BadTmap2{"self-loop", variant("node: B, action", "node: A, action"),
                 "t.tmap2:16: nodes[0].node.edges[0].node: edge 'A_B': the edge leads from node 'A' back to itself "
                 "(self-loops are not allowed)"},
        BadTmap2{"top_vel zero", variant("top_vel: 0.3", "top_vel: 0"),
                 "t.tmap2:25: nodes[1].node.edges[0].top_vel: edge 'B_A': must be a finite speed above 0 m/s, not 0"},
        BadTmap2{"top_vel text", variant("top_vel: 0.3", "top_vel: fast"),
                 "t.tmap2:25: nodes[1].node.edges[0].top_vel: expected a number, found text"},
        BadTmap2{"top_vel in config negative", variant("config: []", "config: {top_vel: -1}"),
                 "t.tmap2:16: nodes[0].node.edges[0].config.top_vel: edge 'A_B': must be a finite speed above 0 m/s, "
                 "not -1"},
        BadTmap2{"meta is text", variant("- meta: {map: map_2d, node: B, pointset: lab}", "- meta: B"),
                 "t.tmap2:17: nodes[1].meta: expected a mapping"},
        BadTmap2{"truncated", kBase.substr(0, kBase.find("yaw_goal_tolerance: 0.2")),
                 "t.tmap2:12: end of map flow not found"}),
    [](const ::testing::TestParamInfo<BadTmap2>& param) {
      std::string name = param.param.what;
      for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
      return name;
    });

}  // namespace
}  // namespace rondo::map
