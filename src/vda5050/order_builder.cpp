#include "rondo/vda5050/order_builder.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

#include "rondo/map/map_geometry.h"

namespace rondo::vda5050 {
namespace {

double wrap_angle(double a) {
  a = std::remainder(a, 2 * std::numbers::pi);  // in [-pi, pi]
  return a;
}

Result<std::vector<map::EdgeIndex>> route_edges(const map::TopoMap& map, const RouteSpec& spec) {
  if (spec.route.empty()) return Error::invalid("route: must have at least one node");
  for (std::size_t i = 0; i < spec.route.size(); ++i) {
    if (spec.route[i] >= map.node_count()) {
      return Error::invalid("route[" + std::to_string(i) + "]: node index " + std::to_string(spec.route[i]) +
                            " is not in map '" + map.name() + "'");
    }
  }
  std::vector<map::EdgeIndex> edges;
  for (std::size_t i = 0; i + 1 < spec.route.size(); ++i) {
    std::optional<map::EdgeIndex> found;
    for (map::EdgeIndex e : map.out_edges(spec.route[i])) {
      if (map.to_index(e) == spec.route[i + 1]) {
        found = e;
        break;
      }
    }
    if (!found) {
      return Error::invalid("route[" + std::to_string(i + 1) + "]: no map edge from '" + map.node(spec.route[i]).name +
                            "' to '" + map.node(spec.route[i + 1]).name + "'");
    }
    edges.push_back(*found);
  }
  if (spec.base_edges > edges.size()) {
    return Error::invalid("base_edges: " + std::to_string(spec.base_edges) + " is more than the route's " +
                          std::to_string(edges.size()) + " edges");
  }
  if (spec.map_id.empty()) return Error::invalid("map_id: must not be empty");
  return edges;
}

std::vector<Action> node_actions(const std::string& order_id, std::int64_t sequence_id,
                                 const std::vector<rondo::Action>& actions) {
  std::vector<Action> out;
  for (std::size_t i = 0; i < actions.size(); ++i) {
    Action a;
    a.action_type = actions[i].name;
    a.action_id = order_id + "/" + std::to_string(sequence_id) + "/" + std::to_string(i);
    a.blocking_type = BlockingType::kHard;
    for (const auto& [key, value] : actions[i].args) {
      a.action_parameters.push_back({key, to_parameter_value(value)});
    }
    out.push_back(std::move(a));
  }
  return out;
}

Result<Order> build(const map::TopoMap& map, const std::string& order_id, std::int64_t order_update_id,
                    std::int64_t first_sequence_id, const RouteSpec& spec) {
  if (order_id.empty()) return Error::invalid("order_id: must not be empty");
  RONDO_ASSIGN_OR_RETURN(auto edges, route_edges(map, spec));
  Order order;
  order.order_id = order_id;
  order.order_update_id = order_update_id;
  for (std::size_t i = 0; i < spec.route.size(); ++i) {
    const map::Node& n = map.node(spec.route[i]);
    OrderNode node;
    node.node_id = n.name;
    node.sequence_id = first_sequence_id + 2 * static_cast<std::int64_t>(i);
    node.released = i <= spec.base_edges;
    node.position = NodePosition{.x = n.pose.x,
                                 .y = n.pose.y,
                                 .theta = wrap_angle(n.pose.yaw),
                                 .allowed_deviation_xy = n.xy_goal_tolerance,
                                 .allowed_deviation_theta = std::min(n.yaw_goal_tolerance, std::numbers::pi),
                                 .map_id = spec.map_id};
    if (i + 1 == spec.route.size()) {
      node.actions = node_actions(order_id, node.sequence_id, spec.final_actions);
    }
    order.nodes.push_back(std::move(node));
  }
  for (std::size_t i = 0; i < edges.size(); ++i) {
    const map::Edge& e = map.edge(edges[i]);
    OrderEdge edge;
    edge.edge_id = e.id;
    edge.sequence_id = first_sequence_id + 2 * static_cast<std::int64_t>(i) + 1;
    edge.released = i < spec.base_edges;
    edge.start_node_id = e.from;
    edge.end_node_id = e.to;
    edge.max_speed = e.top_speed;
    edge.length = map::edge_length(map, edges[i]);
    order.edges.push_back(std::move(edge));
  }
  return order;
}

}  // namespace

Result<Order> build_order(const map::TopoMap& map, const std::string& order_id, const RouteSpec& spec) {
  return build(map, order_id, 0, 0, spec);
}

const OrderNode& last_base_node(const Order& order) {
  std::size_t last = 0;
  while (last + 1 < order.nodes.size() && order.nodes[last + 1].released) ++last;
  return order.nodes.at(last);
}

Result<Order> build_update(const map::TopoMap& map, const Order& previous, const RouteSpec& spec) {
  if (previous.nodes.empty() || !previous.nodes.front().released) {
    return Error::invalid("previous order '" + previous.order_id + "': has no released node to stitch at");
  }
  const OrderNode& stitch = last_base_node(previous);
  if (spec.route.empty() || spec.route.front() >= map.node_count() ||
      map.node(spec.route.front()).name != stitch.node_id) {
    return Error::invalid("route[0]: an update of order '" + previous.order_id +
                          "' must start at its last base node '" + stitch.node_id + "'");
  }
  return build(map, previous.order_id, previous.order_update_id + 1, stitch.sequence_id, spec);
}

ParameterValue to_parameter_value(const std::string& text) {
  if (text == "true") return true;
  if (text == "false") return false;
  double value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value, std::chars_format::general);
  if (!text.empty() && ec == std::errc() && ptr == end && std::isfinite(value)) return value;
  return text;
}

}  // namespace rondo::vda5050
