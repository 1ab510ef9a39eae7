#include "rondo/vda5050/encode.h"

#include "rondo/vda5050/header.h"

namespace rondo::vda5050 {
namespace {

Json encode_value(const ParameterValue& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  if (const auto* d = std::get_if<double>(&v)) return *d;
  return std::get<bool>(v);
}

Json encode_actions(const std::vector<Action>& actions) {
  Json a = Json::array();
  for (const Action& action : actions) a.push_back(encode_action(action));
  return a;
}

Json encode_node(const OrderNode& node, const Compatibility& compat) {
  Json j = Json::object();
  j["nodeId"] = node.node_id;
  j["sequenceId"] = node.sequence_id;
  j["released"] = node.released;
  if (node.position) {
    const NodePosition& p = *node.position;
    Json pos = Json::object();
    pos["x"] = p.x;
    pos["y"] = p.y;
    if (p.theta) pos["theta"] = *p.theta;
    if (p.allowed_deviation_xy > 0) {
      pos["allowedDeviationXY"] = p.allowed_deviation_xy;
      // vda-5050-lib 1.4.0 reads the schema file's spelling (compat.h).
      if (compat.vda5050_lib_1_4) pos["allowedDeviationXy"] = p.allowed_deviation_xy;
    }
    if (p.allowed_deviation_theta > 0) pos["allowedDeviationTheta"] = p.allowed_deviation_theta;
    pos["mapId"] = p.map_id;
    j["nodePosition"] = std::move(pos);
  }
  j["actions"] = encode_actions(node.actions);
  return j;
}

Json encode_edge(const OrderEdge& edge) {
  Json j = Json::object();
  j["edgeId"] = edge.edge_id;
  j["sequenceId"] = edge.sequence_id;
  j["released"] = edge.released;
  j["startNodeId"] = edge.start_node_id;
  j["endNodeId"] = edge.end_node_id;
  if (edge.max_speed) j["maxSpeed"] = *edge.max_speed;
  if (edge.length) j["length"] = *edge.length;
  j["actions"] = encode_actions(edge.actions);
  return j;
}

}  // namespace

Json encode_header(const Header& header) {
  Json j = Json::object();
  j["headerId"] = header.header_id;
  j["timestamp"] = format_timestamp(header.timestamp);
  j["version"] = header.version;
  j["manufacturer"] = header.manufacturer;
  j["serialNumber"] = header.serial_number;
  return j;
}

Json encode_action(const Action& action) {
  Json j = Json::object();
  j["actionType"] = action.action_type;
  j["actionId"] = action.action_id;
  if (!action.action_description.empty()) j["actionDescription"] = action.action_description;
  j["blockingType"] = to_string(action.blocking_type);
  Json params = Json::array();
  for (const ActionParameter& p : action.action_parameters) {
    Json param = Json::object();
    param["key"] = p.key;
    param["value"] = encode_value(p.value);
    params.push_back(std::move(param));
  }
  j["actionParameters"] = std::move(params);
  return j;
}

Json encode_order(const Header& header, const Order& order, const Compatibility& compat) {
  Json j = encode_header(header);
  j["orderId"] = order.order_id;
  j["orderUpdateId"] = order.order_update_id;
  Json nodes = Json::array();
  for (const OrderNode& n : order.nodes) nodes.push_back(encode_node(n, compat));
  Json edges = Json::array();
  for (const OrderEdge& e : order.edges) edges.push_back(encode_edge(e));
  j["nodes"] = std::move(nodes);
  j["edges"] = std::move(edges);
  return j;
}

Json encode_instant_actions(const Header& header, const InstantActions& message, const Compatibility& compat) {
  Json j = encode_header(header);
  j["actions"] = encode_actions(message.actions);
  if (compat.vda5050_lib_1_4) j["instantActions"] = j["actions"];
  return j;
}

Action cancel_order_action(std::string action_id) {
  return Action{.action_type = "cancelOrder",
                .action_id = std::move(action_id),
                .blocking_type = BlockingType::kHard,
                .action_description = "",
                .action_parameters = {}};
}

Action state_request_action(std::string action_id) {
  return Action{.action_type = "stateRequest",
                .action_id = std::move(action_id),
                .blocking_type = BlockingType::kNone,
                .action_description = "",
                .action_parameters = {}};
}

Action factsheet_request_action(std::string action_id) {
  return Action{.action_type = "factsheetRequest",
                .action_id = std::move(action_id),
                .blocking_type = BlockingType::kNone,
                .action_description = "",
                .action_parameters = {}};
}

}  // namespace rondo::vda5050
