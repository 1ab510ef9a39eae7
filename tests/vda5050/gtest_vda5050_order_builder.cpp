// Orders and stitched order updates built from routes: examples on the G4S map and properties
// on random routes over random complete maps.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include "rondo/map/map_loader.h"
#include "rondo/vda5050/order_builder.h"

namespace rondo::vda5050 {
namespace {

map::TopoMap complete_map(int n) {
  std::vector<map::Node> nodes;
  std::vector<map::Edge> edges;
  for (int i = 0; i < n; ++i) {
    nodes.push_back({.name = "N" + std::to_string(i), .pose = {1.0 * i, 0.5 * i * i, 0.1 * i}});
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      map::Edge e;
      e.id = "N" + std::to_string(i) + "_N" + std::to_string(j);
      e.from = "N" + std::to_string(i);
      e.to = "N" + std::to_string(j);
      e.action = "move_base";
      if ((i + j) % 2 == 0) e.top_speed = 0.5;
      edges.push_back(std::move(e));
    }
  }
  return *map::TopoMap::build("complete", std::move(nodes), std::move(edges));
}

// A route of `length` nodes from `start` with no node twice in a row, drawn by RapidCheck.
std::vector<map::NodeIndex> gen_route(std::size_t nodes, map::NodeIndex start, std::size_t length) {
  std::vector<map::NodeIndex> route{start};
  while (route.size() < length) {
    auto step = *rc::gen::inRange<std::size_t>(1, nodes);
    route.push_back((route.back() + step) % nodes);
  }
  return route;
}

// The shape every order must have, whatever the route.
void check_order_shape(const Order& o, const RouteSpec& spec, const map::TopoMap& map, std::int64_t first_sequence) {
  RC_ASSERT(o.nodes.size() == spec.route.size());
  RC_ASSERT(o.edges.size() + 1 == o.nodes.size());
  for (std::size_t i = 0; i < o.nodes.size(); ++i) {
    RC_ASSERT(o.nodes[i].sequence_id == first_sequence + 2 * static_cast<std::int64_t>(i));
    RC_ASSERT(o.nodes[i].sequence_id % 2 == first_sequence % 2);
    RC_ASSERT(o.nodes[i].released == (i <= spec.base_edges));
    RC_ASSERT(o.nodes[i].node_id == map.node(spec.route[i]).name);
    RC_ASSERT(o.nodes[i].position.has_value());
    RC_ASSERT(o.nodes[i].position->map_id == spec.map_id);
    RC_ASSERT(o.nodes[i].actions.empty() == (i + 1 < o.nodes.size() || spec.final_actions.empty()));
  }
  for (std::size_t i = 0; i < o.edges.size(); ++i) {
    const OrderEdge& e = o.edges[i];
    RC_ASSERT(e.sequence_id == o.nodes[i].sequence_id + 1);
    RC_ASSERT(e.sequence_id + 1 == o.nodes[i + 1].sequence_id);
    RC_ASSERT(e.start_node_id == o.nodes[i].node_id);
    RC_ASSERT(e.end_node_id == o.nodes[i + 1].node_id);
    RC_ASSERT(e.released == (i < spec.base_edges));
    // A released edge joins released nodes; an unreleased node has no released edge after it.
    if (e.released) RC_ASSERT(o.nodes[i].released && o.nodes[i + 1].released);
    if (!o.nodes[i].released) RC_ASSERT(!e.released);
    auto me = map.find_edge(e.edge_id);
    RC_ASSERT(me.has_value());
    RC_ASSERT(e.max_speed == map.edge(*me).top_speed);
  }
  // The base is a prefix: released flags never go from false back to true.
  for (std::size_t i = 1; i < o.nodes.size(); ++i) RC_ASSERT(o.nodes[i - 1].released || !o.nodes[i].released);
  for (std::size_t i = 1; i < o.edges.size(); ++i) RC_ASSERT(o.edges[i - 1].released || !o.edges[i].released);
}

RC_GTEST_PROP(Vda5050OrderBuilder, OrdersAndStitchedUpdatesKeepTheirInvariants, ()) {
  const auto n = *rc::gen::inRange<std::size_t>(2, 7);
  const map::TopoMap map = complete_map(static_cast<int>(n));
  RouteSpec spec;
  spec.route = gen_route(n, *rc::gen::inRange<std::size_t>(0, n), *rc::gen::inRange<std::size_t>(1, 9));
  spec.base_edges = *rc::gen::inRange<std::size_t>(0, spec.route.size());
  spec.map_id = "m";
  if (*rc::gen::arbitrary<bool>()) spec.final_actions = {rondo::Action{"noop", {{"duration", "1"}}}};
  auto order = build_order(map, "o", spec);
  RC_ASSERT(order.ok());
  RC_ASSERT(order->order_update_id == 0);
  check_order_shape(*order, spec, map, 0);

  Order previous = *order;
  for (int update = 1; update <= 3; ++update) {
    const OrderNode& stitch = last_base_node(previous);
    RouteSpec next;
    next.route = gen_route(n, *map.find_node(stitch.node_id), *rc::gen::inRange<std::size_t>(1, 8));
    next.base_edges = *rc::gen::inRange<std::size_t>(0, next.route.size());
    next.map_id = "m";
    auto u = build_update(map, previous, next);
    RC_ASSERT(u.ok());
    RC_ASSERT(u->order_id == previous.order_id);
    RC_ASSERT(u->order_update_id == previous.order_update_id + 1);
    // The stitch: the first node is the previous last base node, same sequenceId, released.
    RC_ASSERT(u->nodes.front().node_id == stitch.node_id);
    RC_ASSERT(u->nodes.front().sequence_id == stitch.sequence_id);
    RC_ASSERT(u->nodes.front().released);
    check_order_shape(*u, next, map, stitch.sequence_id);
    // The base only grows: the new last base node is at or after the old one.
    RC_ASSERT(last_base_node(*u).sequence_id >= stitch.sequence_id);
    previous = *u;
  }
}

TEST(Vda5050OrderBuilder, OnTheG4sMap) {
  auto map = map::load_map("examples/g4s/map.yaml");
  ASSERT_TRUE(map.ok()) << map.error().message;
  // The first three-edge path (by node and edge order) that never steps straight back.
  std::vector<map::NodeIndex> route;
  for (map::NodeIndex a = 0; a < map->node_count() && route.empty(); ++a) {
    for (map::EdgeIndex e1 : map->out_edges(a)) {
      const map::NodeIndex b = map->to_index(e1);
      for (map::EdgeIndex e2 : map->out_edges(b)) {
        const map::NodeIndex c = map->to_index(e2);
        if (c == a) continue;
        for (map::EdgeIndex e3 : map->out_edges(c)) {
          if (map->to_index(e3) != b && route.empty()) route = {a, b, c, map->to_index(e3)};
        }
      }
    }
  }
  ASSERT_EQ(route.size(), 4u);
  RouteSpec spec{.route = route,
                 .base_edges = 1,
                 .map_id = "g4s_y2",
                 .final_actions = {rondo::Action{"check_door", {{"door", "fd3"}, {"duration", "2.5"}}}}};
  auto o = build_order(*map, "nav-1", spec);
  ASSERT_TRUE(o.ok()) << o.error().message;
  EXPECT_EQ(o->nodes[0].node_id, map->node(route[0]).name);
  EXPECT_TRUE(o->nodes[1].released);
  EXPECT_FALSE(o->nodes[2].released);
  EXPECT_TRUE(o->edges[0].released);
  EXPECT_FALSE(o->edges[1].released);
  EXPECT_GT(*o->edges[0].length, 0.0);
  const Action& a = o->nodes[3].actions.at(0);
  EXPECT_EQ(a.action_type, "check_door");
  EXPECT_EQ(a.action_id, "nav-1/6/0");
  EXPECT_EQ(a.blocking_type, BlockingType::kHard);
  ASSERT_EQ(a.action_parameters.size(), 2u);
  EXPECT_EQ(a.action_parameters[0].key, "door");
  EXPECT_EQ(a.action_parameters[0].value, ParameterValue(std::string("fd3")));
  EXPECT_EQ(a.action_parameters[1].value, ParameterValue(2.5));

  // The horizon is replaced at the decision point: route[1] and then straight back.
  RouteSpec back{.route = {route[1], route[0]}, .base_edges = 1, .map_id = "g4s_y2", .final_actions = {}};
  auto u = build_update(*map, *o, back);
  ASSERT_TRUE(u.ok()) << u.error().message;
  EXPECT_EQ(u->order_update_id, 1);
  EXPECT_EQ(u->nodes[0].sequence_id, 2);
  EXPECT_EQ(u->nodes[1].sequence_id, 4);
  EXPECT_EQ(u->edges[0].sequence_id, 3);
}

TEST(Vda5050OrderBuilder, BadRoutesAreErrors) {
  const map::TopoMap map = complete_map(3);
  auto err = [&](RouteSpec s) {
    auto o = build_order(map, "o", s);
    return o.ok() ? std::string() : o.error().message;
  };
  EXPECT_NE(err({.route = {}, .base_edges = 0, .map_id = "m", .final_actions = {}}).find("at least one"),
            std::string::npos);
  EXPECT_NE(err({.route = {0, 7}, .base_edges = 0, .map_id = "m", .final_actions = {}}).find("route[1]"),
            std::string::npos);
  EXPECT_NE(err({.route = {0, 0}, .base_edges = 0, .map_id = "m", .final_actions = {}}).find("no map edge"),
            std::string::npos);
  EXPECT_NE(err({.route = {0, 1}, .base_edges = 2, .map_id = "m", .final_actions = {}}).find("base_edges"),
            std::string::npos);
  EXPECT_NE(err({.route = {0, 1}, .base_edges = 1, .map_id = "", .final_actions = {}}).find("map_id"),
            std::string::npos);
  auto o = build_order(map, "o", {.route = {0, 1, 2}, .base_edges = 1, .map_id = "m", .final_actions = {}});
  ASSERT_TRUE(o.ok());
  auto u = build_update(map, *o, {.route = {2, 0}, .base_edges = 1, .map_id = "m", .final_actions = {}});
  ASSERT_FALSE(u.ok());
  EXPECT_NE(u.error().message.find("last base node 'N1'"), std::string::npos);
}

TEST(Vda5050OrderBuilder, ParameterValuesAreTyped) {
  EXPECT_EQ(to_parameter_value("true"), ParameterValue(true));
  EXPECT_EQ(to_parameter_value("-0.5"), ParameterValue(-0.5));
  EXPECT_EQ(to_parameter_value("1e3"), ParameterValue(1000.0));
  EXPECT_EQ(to_parameter_value("2 m"), ParameterValue(std::string("2 m")));
  EXPECT_EQ(to_parameter_value(""), ParameterValue(std::string()));
  EXPECT_EQ(to_parameter_value("nan"), ParameterValue(std::string("nan")));
}

}  // namespace
}  // namespace rondo::vda5050
