// rondo's own map format: reading (strict, located errors), writing, and the round trip.
#include "rondo/map/map_yaml.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <limits>

#include "map_test_support.h"
#include "rondo/core/document.h"

namespace rondo::map {
namespace {

using testing::fixture;

TEST(MapYaml, ReadsEveryFieldOfTheOfficeFixture) {
  auto text = read_text_file(fixture("office.yaml"));
  ASSERT_TRUE(text.ok());
  auto map = parse_map_yaml(*text, "office.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->name(), "office");
  ASSERT_EQ(map->node_count(), 5u);
  ASSERT_EQ(map->edge_count(), 8u);

  const Node& charger = map->node(*map->find_node("ChargingPoint"));
  EXPECT_EQ(charger.pose, (Pose{0.0, 0.0, 3.14159}));
  EXPECT_DOUBLE_EQ(charger.xy_goal_tolerance, 0.05);
  EXPECT_DOUBLE_EQ(charger.yaw_goal_tolerance, 0.05);

  const Node& corridor = map->node(*map->find_node("Corridor"));
  EXPECT_EQ(corridor.pose.yaw, 0.0);  // yaw defaults to 0
  EXPECT_DOUBLE_EQ(corridor.xy_goal_tolerance, kDefaultXyGoalTolerance);
  EXPECT_EQ(corridor.influence, (std::vector<Point2>{{1.0, 0.5}, {-1.0, 0.5}, {-1.0, -0.5}, {1.0, -0.5}}));
  EXPECT_TRUE(corridor.meta.is_null());

  const Node& kitchen = map->node(*map->find_node("Kitchen"));
  EXPECT_EQ(kitchen.meta["description"], "Kitchen with the coffee machine");
  EXPECT_EQ(kitchen.meta["contains"][0]["name"], "K-1");

  const Edge& dock = map->edge(0);
  EXPECT_EQ(dock.id, "Station_ChargingPoint");
  EXPECT_EQ(dock.action, "docking");
  EXPECT_EQ(dock.top_speed, 0.1);
  const Edge& station_corridor = map->edge(*map->find_edge("Station_Corridor"));  // id defaults to from_to
  EXPECT_EQ(station_corridor.action, "move_base");                                // action defaults
  EXPECT_FALSE(station_corridor.top_speed.has_value());
  EXPECT_EQ(map->edge(*map->find_edge("Kitchen_Corridor")).door, "kitchen_door");
}

TEST(MapYaml, MinimalMapNeedsOnlyNamesPositionsAndEnds) {
  auto map = parse_map_yaml("nodes: [{name: A, pose: {x: 0, y: 0}}]\n", "m.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->node_count(), 1u);
  EXPECT_EQ(map->edge_count(), 0u);
  EXPECT_EQ(map->name(), "");
}

TEST(MapYaml, DetectsItsOwnDocuments) {
  const std::vector<std::pair<std::string, bool>> cases = {{"rondo_map: 1\n", true},
                                                           {"nodes: []\n", true},
                                                           {"- meta: {}\n  node: {}\n", false},
                                                           {"name: x\n", false},
                                                           {"42\n", false}};
  for (const auto& [text, expected] : cases) {
    auto doc = Document::parse(text, DocumentFormat::kYaml, "t.yaml");
    ASSERT_TRUE(doc.ok());
    EXPECT_EQ(is_rondo_map_document(*doc), expected) << text;
  }
}

struct BadMap {
  const char* what;
  std::string text;
  std::string expected;  // the whole error message
};

class MapYamlErrors : public ::testing::TestWithParam<BadMap> {};

TEST_P(MapYamlErrors, NameFileLineFieldAndProblem) {
  const BadMap& c = GetParam();
  auto map = parse_map_yaml(c.text, "bad.yaml");
  ASSERT_FALSE(map.ok()) << c.what;
  EXPECT_EQ(map.error().code, ErrorCode::kInvalidInput) << c.what;
  EXPECT_EQ(map.error().message, c.expected) << c.what;
}

const std::string kTwoNodes =
    "rondo_map: 1\nnodes:\n  - {name: A, pose: {x: 0, y: 0}}\n  - {name: B, pose: {x: 1, y: 0}}\n";

INSTANTIATE_TEST_SUITE_P(
    Malformed, MapYamlErrors,
    ::testing::Values(
        BadMap{"truncated YAML", "rondo_map: 1\nnodes:\n  - {name: A, pose: {x: 0, y:", "bad.yaml:3: unknown token"},
        BadMap{"garbage bytes", "\x7f\x45LF\x02\x01\x01\xff\xfe\x00\x00", "bad.yaml:1: the text is not valid UTF-8"},
        BadMap{"empty file", "",
               "bad.yaml: expected a rondo map: a mapping with 'rondo_map', 'name', 'nodes' and 'edges'"},
        BadMap{"a list at the top", "- a\n- b\n",
               "bad.yaml:1: expected a rondo map: a mapping with 'rondo_map', 'name', 'nodes' and 'edges'"},
        BadMap{"unknown top-level field", "rondo_map: 1\nnodes: []\nfloors: 2\n",
               "bad.yaml:3: floors: unknown field 'floors' (expected one of: rondo_map, name, nodes, edges)"},
        BadMap{"newer version", "rondo_map: 2\nnodes: []\n",
               "bad.yaml:1: rondo_map: format version 2 is not supported: this build reads version 1"},
        BadMap{"version as text", "rondo_map: one\nnodes: []\n",
               "bad.yaml:1: rondo_map: expected the format version, an integer such as 1"},
        BadMap{"missing nodes", "rondo_map: 1\nname: x\n", "bad.yaml:1: missing field 'nodes'"},
        BadMap{"no nodes", "rondo_map: 1\nnodes: []\n", "bad.yaml:2: nodes: a map needs at least one node"},
        BadMap{"nodes not a list", "rondo_map: 1\nnodes: {A: 1}\n", "bad.yaml:2: nodes: expected a list"},
        BadMap{"missing pose", "nodes:\n  - name: A\n", "bad.yaml:2: nodes[0]: missing field 'pose'"},
        BadMap{"missing y", "nodes:\n  - name: A\n    pose: {x: 1}\n", "bad.yaml:3: nodes[0].pose: missing field 'y'"},
        BadMap{"wrong type x", "nodes:\n  - name: A\n    pose: {x: one, y: 0}\n",
               "bad.yaml:3: nodes[0].pose.x: expected a number, found text"},
        BadMap{"name is a number", "nodes:\n  - name: 12\n    pose: {x: 1, y: 0}\n",
               "bad.yaml:2: nodes[0].name: expected text, found an integer"},
        BadMap{"unknown node field", "nodes:\n  - name: A\n    pose: {x: 1, y: 0}\n    colour: red\n",
               "bad.yaml:4: nodes[0].colour: unknown field 'colour' (expected one of: name, pose, xy_goal_tolerance, "
               "yaw_goal_tolerance, influence, meta, capacity)"},
        BadMap{"unknown pose field", "nodes:\n  - name: A\n    pose: {x: 1, y: 0, z: 0}\n",
               "bad.yaml:3: nodes[0].pose.z: unknown field 'z' (expected one of: x, y, yaw)"},
        BadMap{"influence vertex without y",
               "nodes:\n  - name: A\n    pose: {x: 1, y: 0}\n    influence:\n      - {x: 1}\n",
               "bad.yaml:5: nodes[0].influence[0]: missing field 'y'"},
        BadMap{"meta not a mapping", "nodes:\n  - name: A\n    pose: {x: 1, y: 0}\n    meta: [1, 2]\n",
               "bad.yaml:4: nodes[0].meta: expected a mapping of free-form facts about the place"},
        BadMap{"negative tolerance", "nodes:\n  - name: A\n    pose: {x: 1, y: 0}\n    xy_goal_tolerance: -1\n",
               "bad.yaml:4: nodes[0].xy_goal_tolerance: must be a finite number of metres, 0 or more"},
        BadMap{"duplicate node", kTwoNodes + "  - {name: A, pose: {x: 2, y: 0}}\n",
               "bad.yaml:5: nodes[2].name: node 'A' is already defined by nodes[0]"},
        BadMap{"unknown node reference", kTwoNodes + "edges:\n  - {from: A, to: B}\n  - {from: B, to: Lab}\n",
               "bad.yaml:7: edges[1].to: no node named 'Lab'"},
        BadMap{"unknown source", kTwoNodes + "edges:\n  - {from: Q, to: B}\n",
               "bad.yaml:6: edges[0].from: no node named 'Q'"},
        BadMap{"self-loop", kTwoNodes + "edges:\n  - {from: A, to: A}\n",
               "bad.yaml:6: edges[0].to: the edge leads from node 'A' back to itself (self-loops are not allowed)"},
        BadMap{"duplicate edge id", kTwoNodes + "edges:\n  - {from: A, to: B}\n  - {id: A_B, from: B, to: A}\n",
               "bad.yaml:7: edges[1].id: edge id 'A_B' is already used by edges[0]"},
        BadMap{"default id collides",
               kTwoNodes + "edges:\n  - {from: A, to: B}\n  - {from: A, to: B, action: docking}\n",
               "bad.yaml:7: edges[1].id: edge id 'A_B' is already used by edges[0]"},
        BadMap{"negative speed", kTwoNodes + "edges:\n  - {from: A, to: B, top_speed: -0.5}\n",
               "bad.yaml:6: edges[0].top_speed: must be a finite speed above 0 m/s, not -0.5"},
        BadMap{"speed as text", kTwoNodes + "edges:\n  - {from: A, to: B, top_speed: fast}\n",
               "bad.yaml:6: edges[0].top_speed: expected a number, found text"},
        BadMap{"missing to", kTwoNodes + "edges:\n  - {from: A}\n", "bad.yaml:6: edges[0]: missing field 'to'"},
        BadMap{"unknown edge field", kTwoNodes + "edges:\n  - {from: A, to: B, speed: 1}\n",
               "bad.yaml:6: edges[0].speed: unknown field 'speed' (expected one of: id, from, to, action, top_speed, "
               "door, narrow)"},
        BadMap{"capacity 0", "nodes:\n  - name: A\n    pose: {x: 1, y: 0}\n    capacity: 0\n",
               "bad.yaml:4: nodes[0].capacity: expected a whole number of robots the place holds at once, from 1 to "
               "1000, not 0"},
        BadMap{"capacity as text", "nodes:\n  - name: A\n    pose: {x: 1, y: 0}\n    capacity: two\n",
               "bad.yaml:4: nodes[0].capacity: expected a whole number of robots the place holds at once, from 1 to "
               "1000"},
        BadMap{"capacity a fraction", kTwoNodes + "  - {name: C, pose: {x: 2, y: 0}, capacity: 1.5}\n",
               "bad.yaml:5: nodes[2].capacity: expected a whole number of robots the place holds at once, from 1 to "
               "1000"},
        BadMap{"narrow wide", kTwoNodes + "edges:\n  - {from: A, to: B}\n  - {from: B, to: A, narrow: wide}\n",
               "bad.yaml:7: edges[1].narrow: expected single (one robot at a time) or one_way (one direction at a "
               "time)"},
        BadMap{"narrow as a flag", kTwoNodes + "edges:\n  - {from: A, to: B, narrow: true}\n",
               "bad.yaml:6: edges[0].narrow: expected single (one robot at a time) or one_way (one direction at a "
               "time)"},
        BadMap{"edges not a list", kTwoNodes + "edges: A_B\n", "bad.yaml:5: edges: expected a list"},
        BadMap{"several problems", kTwoNodes + "edges:\n  - {from: A, to: X}\n  - {from: A, to: Y}\n",
               "bad.yaml:6: edges[0].to: no node named 'X' (and 1 more problems)"}));

TEST(MapYaml, ReadsAndWritesCapacityAndNarrowEdges) {
  const std::string text = kTwoNodes +
                           "  - {name: Atrium, pose: {x: 2, y: 0}, capacity: 3}\n"
                           "edges:\n"
                           "  - {from: A, to: B, narrow: single}\n"
                           "  - {from: B, to: A, narrow: single}\n"
                           "  - {from: B, to: Atrium, narrow: one_way}\n"
                           "  - {from: Atrium, to: B}\n";
  auto map = parse_map_yaml(text, "m.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  EXPECT_EQ(map->node(0).capacity, 1);  // the default: one robot at a time
  EXPECT_EQ(map->node(2).capacity, 3);
  EXPECT_EQ(map->edge(0).narrow, Narrow::kSingle);
  EXPECT_EQ(map->edge(2).narrow, Narrow::kOneWay);
  EXPECT_EQ(map->edge(3).narrow, Narrow::kNone);        // absent: robots pass each other
  EXPECT_EQ(passage_narrow(*map, 3), Narrow::kOneWay);  // its reverse marks the passage
  const std::string written = write_map_yaml(*map);
  EXPECT_NE(written.find("capacity: 3"), std::string::npos) << written;
  EXPECT_NE(written.find("narrow: one_way"), std::string::npos) << written;
  EXPECT_EQ(written.find("capacity: 1"), std::string::npos) << written;  // the default is not written
  EXPECT_EQ(written.find("narrow: none"), std::string::npos) << written;
  auto again = parse_map_yaml(written, "again.yaml");
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(*again, *map);
}

TEST(MapYaml, WriterOmitsAbsentOptionalsAndQuotesTrickyText) {
  Node a = testing::node_at("true", 0, 0);
  Node b = testing::node_at("1.5", 1, 0);
  auto map = TopoMap::build("null", {a, b}, {testing::edge("true", "1.5")});
  ASSERT_TRUE(map.ok());
  const std::string text = write_map_yaml(*map);
  EXPECT_EQ(text.rfind("# rondo topological map, format version 1", 0), 0u);
  EXPECT_EQ(text.find("influence"), std::string::npos);
  EXPECT_EQ(text.find("meta"), std::string::npos);
  EXPECT_EQ(text.find("top_speed"), std::string::npos);
  EXPECT_NE(text.find("name: \"true\""), std::string::npos) << text;
  auto again = parse_map_yaml(text, "again.yaml");
  ASSERT_TRUE(again.ok()) << again.error().message << "\n" << text;
  EXPECT_EQ(*again, *map);
}

TEST(MapYaml, OfficeFixtureRoundTrips) {
  auto map = parse_map_yaml(*read_text_file(fixture("office.yaml")), "office.yaml");
  ASSERT_TRUE(map.ok());
  auto again = parse_map_yaml(write_map_yaml(*map), "again.yaml");
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(*again, *map);
}

// Regression: Document::parse once counted '[' inside text towards its nesting limit, so a map
// with more than 64 names like "Room [3" could not be read back.
TEST(MapYaml, ManyNamesWithOpeningBracketsRoundTrip) {
  std::vector<Node> nodes;
  for (int i = 0; i < 70; ++i) nodes.push_back(testing::node_at("Room [" + std::to_string(i), i, 0));
  const TopoMap map = testing::build_or_fail(std::move(nodes), {});
  auto again = parse_map_yaml(write_map_yaml(map), "again.yaml");
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(*again, map);
}

// --- RapidCheck: any valid map survives write -> read unchanged. ---

rc::Gen<std::string> gen_text() {
  // Pieces that YAML treats specially, so the writer's quoting is exercised.
  static const std::vector<std::string> pieces = {
      "A", "WayPoint", "7",    "1.5", "1e3", "true", "null", "~", "- ", "#", ": ", "'",           "\"",           "}",
      "]", ",",        "&",    "*",   "!",   "%",    "@",    "`", "|",  ">", " ",  "caf\xc3\xa9", "\xe6\xbc\xa2", "\\",
      "?", "yes",      "0x1F", "-",  "[", "{"};
  return rc::gen::map(rc::gen::container<std::vector<std::string>>(rc::gen::elementOf(pieces)),
                      [](const std::vector<std::string>& parts) {
                        std::string s;
                        for (const auto& p : parts) s += p;
                        return s;
                      });
}

rc::Gen<double> gen_finite() {
  return rc::gen::oneOf(rc::gen::element(0.0, -0.0, 1e300, -1e-300, 5e-324, 0.1, 1.0 / 3.0, 2.0, -47.1828079224),
                        rc::gen::map(rc::gen::arbitrary<int>(), [](int i) { return i / 1000.0; }),
                        rc::gen::suchThat(rc::gen::arbitrary<double>(), [](double d) { return std::isfinite(d); }));
}

rc::Gen<Json> gen_meta() {
  return rc::gen::exec([] {
    Json meta = Json::object();
    const auto count = *rc::gen::inRange<std::size_t>(1, 4);
    for (std::size_t i = 0; i < count; ++i) {
      const std::string key = *gen_text();
      switch (*rc::gen::inRange(0, 6)) {
        case 0:
          meta[key] = *gen_text();
          break;
        case 1:
          meta[key] = *gen_finite();
          break;
        case 2:
          meta[key] = *rc::gen::arbitrary<bool>();
          break;
        case 3:
          meta[key] = nullptr;
          break;
        case 4:
          meta[key] = Json::array({*gen_text(), *rc::gen::arbitrary<int>()});
          break;
        default:
          meta[key] = Json{{"name", *gen_text()}, {"at_node", true}};
          break;
      }
    }
    return meta;
  });
}

rc::Gen<TopoMap> gen_map() {
  return rc::gen::exec([] {
    const auto count = *rc::gen::inRange<std::size_t>(1, 10);
    std::vector<Node> nodes;
    for (std::size_t i = 0; i < count; ++i) {
      Node n;
      n.name = *gen_text();
      if (n.name.empty()) n.name = "n";
      for (const Node& other : nodes) {
        if (other.name == n.name) n.name += "#" + std::to_string(i);
      }
      n.pose = {*gen_finite(), *gen_finite(), *gen_finite()};
      n.xy_goal_tolerance = std::abs(*gen_finite());
      n.yaw_goal_tolerance = std::abs(*gen_finite());
      const auto vertices = *rc::gen::inRange<std::size_t>(0, 4);
      for (std::size_t v = 0; v < vertices; ++v) n.influence.push_back({*gen_finite(), *gen_finite()});
      if (*rc::gen::arbitrary<bool>()) n.meta = *gen_meta();
      nodes.push_back(std::move(n));
    }
    std::vector<Edge> edges;
    if (count >= 2) {
      const auto edge_count = *rc::gen::inRange<std::size_t>(0, 3 * count);
      for (std::size_t k = 0; k < edge_count; ++k) {
        const auto from = *rc::gen::inRange<std::size_t>(0, count);
        const auto to = (from + *rc::gen::inRange<std::size_t>(1, count)) % count;
        Edge e;
        e.from = nodes[from].name;
        e.to = nodes[to].name;
        e.id = *rc::gen::arbitrary<bool>() ? e.from + "_" + e.to + "#" + std::to_string(k) : "e" + std::to_string(k);
        e.action = *rc::gen::element<std::string>("move_base", "human_aware_navigation", "doorPassing", "docking",
                                                  "true", "12");
        if (*rc::gen::arbitrary<bool>()) e.top_speed = 0.01 + std::abs(*gen_finite()) / 1e3;
        if (*rc::gen::arbitrary<bool>()) e.door = "door " + *gen_text();
        edges.push_back(std::move(e));
      }
    }
    auto map = TopoMap::build(*gen_text(), std::move(nodes), std::move(edges));
    RC_ASSERT(map.ok());
    return *map;
  });
}

RC_GTEST_PROP(MapYamlProperty, WriteThenReadGivesTheSameMap, ()) {
  const TopoMap map = *gen_map();
  const std::string text = write_map_yaml(map);
  auto again = parse_map_yaml(text, "roundtrip.yaml");
  if (!again.ok()) RC_FAIL(again.error().message + "\n" + text);
  if (!(*again == map)) RC_FAIL("read back differently:\n" + text + "\n" + write_map_yaml(*again));
}

}  // namespace
}  // namespace rondo::map
