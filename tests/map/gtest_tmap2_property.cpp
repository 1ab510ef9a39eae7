// Property: any map written in the tmap2 form (as topological_navigation's map manager writes it)
// imports as exactly that map, and the import survives rondo's format unchanged.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/map/map_geometry.h"
#include "rondo/map/map_yaml.h"
#include "rondo/map/strands_import.h"
#include "rondo/map/tmap2_import.h"

namespace rondo::map {
namespace {

struct Written {
  std::string text;
  std::vector<Node> nodes;
  std::vector<Edge> edges;
};

const std::vector<std::string> kActions = {"move_base",          "NavigateToPose", "row_traversal",
                                           "door_wait_and_move", "dock",           "row_change/move_base"};

// A random map, and its tmap2 text in the shape of the real files.
Written random_tmap2() {
  Written w;
  const auto n = *rc::gen::inRange<std::size_t>(1, 10);
  Json nodes = Json::array();
  for (std::size_t i = 0; i < n; ++i) {
    // Some names are bare integers in the file, as unquoted YAML names can be.
    const bool numeric = *rc::gen::inRange(0, 4) == 0;
    Node node;
    node.name = numeric ? std::to_string(100 + i) : "N" + std::to_string(i);
    node.pose = {*rc::gen::inRange(-100000, 100000) / 100.0, *rc::gen::inRange(-100000, 100000) / 100.0,
                 *rc::gen::inRange(-3141, 3141) / 1000.0};
    node.xy_goal_tolerance = *rc::gen::inRange(0, 300) / 100.0;
    node.yaw_goal_tolerance = *rc::gen::inRange(0, 628) / 100.0;
    Json verts = Json::array();
    for (int v = *rc::gen::inRange(0, 6); v > 0; --v) {
      node.influence.push_back({*rc::gen::inRange(-200, 200) / 100.0, *rc::gen::inRange(-200, 200) / 100.0});
      verts.push_back({{"x", node.influence.back().x}, {"y", node.influence.back().y}});
    }
    const double half = node.pose.yaw / 2;
    Json entry = {{"meta", {{"map", "map_2d"}, {"node", node.name}, {"pointset", "prop"}}},
                  {"node",
                   {{"name", numeric ? Json(100 + i) : Json(node.name)},
                    {"pose",
                     {{"position", {{"x", node.pose.x}, {"y", node.pose.y}, {"z", 0.0}}},
                      {"orientation", {{"x", 0.0}, {"y", 0.0}, {"z", std::sin(half)}, {"w", std::cos(half)}}}}},
                    {"properties",
                     {{"xy_goal_tolerance", node.xy_goal_tolerance}, {"yaw_goal_tolerance", node.yaw_goal_tolerance}}},
                    {"verts", verts},
                    {"localise_by_topic", ""},
                    {"restrictions_planning", "True"},
                    {"restrictions_runtime", "True"},
                    {"edges", Json::array()}}}};
    nodes.push_back(entry);
    w.nodes.push_back(node);
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j || *rc::gen::inRange(0, 3) != 0) continue;
      Edge e;
      e.from = w.nodes[i].name;
      e.to = w.nodes[j].name;
      e.id = e.from + "_" + e.to;
      e.action = *rc::gen::elementOf(kActions);
      Json edge = {{"action", e.action}, {"action_type", "move_base_msgs/MoveBaseGoal"}, {"config", Json::array()}};
      if (*rc::gen::arbitrary<bool>()) edge["edge_id"] = e.id;  // else the importer names it the same way
      edge["fail_policy"] = "fail";
      edge["node"] = e.to;
      if (*rc::gen::arbitrary<bool>()) {
        e.top_speed = *rc::gen::inRange(1, 300) / 100.0;
        edge["top_vel"] = *e.top_speed;
      }
      edge["restrictions_planning"] = "True";
      if (action_kind(e.action) == ActionKind::kDoor) e.door = door_id_between(e.from, e.to);
      nodes[i]["node"]["edges"].push_back(edge);
      w.edges.push_back(e);
    }
  }
  const Json root = {{"meta", {{"last_updated", "2024-01-01_00-00-00"}}},
                     {"metric_map", "map_2d"},
                     {"name", "prop"},
                     {"nodes", nodes},
                     {"pointset", "prop"}};
  w.text = to_yaml(root);
  return w;
}

double angle_between(double a, double b) {
  const double d = std::remainder(a - b, 2 * std::numbers::pi);
  return std::abs(d);
}

RC_GTEST_PROP(Tmap2Properties, ImportsExactlyTheMapThatWasWritten, ()) {
  const Written w = random_tmap2();
  auto in = parse_tmap2(w.text, "prop.tmap2");
  RC_ASSERT(in.ok());
  const TopoMap& map = in->map;
  RC_ASSERT(map.name() == "prop");
  RC_ASSERT(map.node_count() == w.nodes.size());
  for (std::size_t i = 0; i < w.nodes.size(); ++i) {
    const Node& got = map.node(i);
    const Node& want = w.nodes[i];
    RC_ASSERT(got.name == want.name);
    RC_ASSERT(got.pose.x == want.pose.x);
    RC_ASSERT(got.pose.y == want.pose.y);
    RC_ASSERT(angle_between(got.pose.yaw, want.pose.yaw) < 1e-9);
    RC_ASSERT(got.xy_goal_tolerance == want.xy_goal_tolerance);
    RC_ASSERT(got.yaw_goal_tolerance == want.yaw_goal_tolerance);
    RC_ASSERT(got.influence == want.influence);
    RC_ASSERT(got.meta.is_null());
  }
  RC_ASSERT(map.edges() == w.edges);
  RC_ASSERT(in->warnings.empty());
  auto again = parse_map_yaml(write_map_yaml(map), "again.yaml");
  RC_ASSERT(again.ok());
  RC_ASSERT(*again == map);
}

}  // namespace
}  // namespace rondo::map
