#include "rondo/vda5050/decode.h"

#include <algorithm>
#include <string>

#include "rondo/core/document.h"

namespace rondo::vda5050 {
namespace {

// A Document rejects the nesting depth before recursing; the source names the topic in errors.
Result<Field> parse_object(std::string_view payload, std::string_view topic) {
  auto doc = Document::parse(payload, DocumentFormat::kJson, std::string(topic));
  if (!doc) return doc.error();
  Field root = doc->root();
  if (!root.is_object()) return root.error("the message must be a JSON object");
  return root;
}

Result<std::string> req_string(const Field& f, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(Field v, f.required(key));
  return v.as_string();
}

Result<std::int64_t> req_int(const Field& f, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(Field v, f.required(key));
  return v.as_int();
}

Result<double> req_number(const Field& f, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(Field v, f.required(key));
  return v.as_number();
}

Result<bool> req_bool(const Field& f, std::string_view key) {
  RONDO_ASSIGN_OR_RETURN(Field v, f.required(key));
  return v.as_bool();
}

Result<std::string> opt_string(const Field& f, std::string_view key) {
  auto v = f.optional(key);
  if (!v) return std::string();
  return v->as_string();
}

Result<std::vector<Field>> opt_items(const Field& f, std::string_view key) {
  auto v = f.optional(key);
  if (!v) return std::vector<Field>{};
  return v->items();
}

Result<Header> decode_header(const Field& root) {
  Header h;
  RONDO_ASSIGN_OR_RETURN(h.header_id, req_int(root, "headerId"));
  if (h.header_id < 0) return root.error_at("headerId", "must not be negative");
  RONDO_ASSIGN_OR_RETURN(Field ts, root.required("timestamp"));
  RONDO_ASSIGN_OR_RETURN(h.timestamp, ts.as_time(nullptr));
  RONDO_ASSIGN_OR_RETURN(h.version, req_string(root, "version"));
  if (h.version.rfind("2.", 0) != 0) {
    return root.error_at("version", "'" + h.version + "' is not a 2.x version of VDA 5050");
  }
  RONDO_ASSIGN_OR_RETURN(h.manufacturer, req_string(root, "manufacturer"));
  RONDO_ASSIGN_OR_RETURN(h.serial_number, req_string(root, "serialNumber"));
  return h;
}

template <class E>
Result<E> parse_enum(const Field& f, std::string_view key,
                     std::initializer_list<std::pair<std::string_view, E>> values) {
  RONDO_ASSIGN_OR_RETURN(std::string text, req_string(f, key));
  for (const auto& [name, value] : values) {
    if (text == name) return value;
  }
  return f.error_at(key, "unknown value '" + text + "'");
}

Result<std::vector<NodeState>> decode_node_states(const Field& root) {
  RONDO_ASSIGN_OR_RETURN(Field list, root.required("nodeStates"));
  RONDO_ASSIGN_OR_RETURN(auto items, list.items());
  std::vector<NodeState> out;
  for (const Field& n : items) {
    NodeState s;
    RONDO_ASSIGN_OR_RETURN(s.node_id, req_string(n, "nodeId"));
    RONDO_ASSIGN_OR_RETURN(s.sequence_id, req_int(n, "sequenceId"));
    RONDO_ASSIGN_OR_RETURN(s.released, req_bool(n, "released"));
    out.push_back(std::move(s));
  }
  return out;
}

Result<std::vector<EdgeState>> decode_edge_states(const Field& root) {
  RONDO_ASSIGN_OR_RETURN(Field list, root.required("edgeStates"));
  RONDO_ASSIGN_OR_RETURN(auto items, list.items());
  std::vector<EdgeState> out;
  for (const Field& e : items) {
    EdgeState s;
    RONDO_ASSIGN_OR_RETURN(s.edge_id, req_string(e, "edgeId"));
    RONDO_ASSIGN_OR_RETURN(s.sequence_id, req_int(e, "sequenceId"));
    RONDO_ASSIGN_OR_RETURN(s.released, req_bool(e, "released"));
    out.push_back(std::move(s));
  }
  return out;
}

Result<std::vector<ActionState>> decode_action_states(const Field& root) {
  RONDO_ASSIGN_OR_RETURN(Field list, root.required("actionStates"));
  RONDO_ASSIGN_OR_RETURN(auto items, list.items());
  std::vector<ActionState> out;
  for (const Field& a : items) {
    ActionState s;
    RONDO_ASSIGN_OR_RETURN(s.action_id, req_string(a, "actionId"));
    RONDO_ASSIGN_OR_RETURN(s.action_type, opt_string(a, "actionType"));
    RONDO_ASSIGN_OR_RETURN(s.action_status, parse_enum<ActionStatus>(a, "actionStatus",
                                                                     {{"WAITING", ActionStatus::kWaiting},
                                                                      {"INITIALIZING", ActionStatus::kInitializing},
                                                                      {"RUNNING", ActionStatus::kRunning},
                                                                      {"PAUSED", ActionStatus::kPaused},
                                                                      {"FINISHED", ActionStatus::kFinished},
                                                                      {"FAILED", ActionStatus::kFailed}}));
    RONDO_ASSIGN_OR_RETURN(s.result_description, opt_string(a, "resultDescription"));
    out.push_back(std::move(s));
  }
  return out;
}

// A referenceValue: a string in the schema; some vehicles send numbers: keep their text.
Result<ErrorReference> decode_reference(const Field& r) {
  ErrorReference ref;
  RONDO_ASSIGN_OR_RETURN(ref.reference_key, req_string(r, "referenceKey"));
  RONDO_ASSIGN_OR_RETURN(Field value, r.required("referenceValue"));
  if (value.is_string()) {
    ref.reference_value = value.json().get<std::string>();
  } else if (value.json().is_primitive() && !value.is_null()) {
    ref.reference_value = value.json().dump();
  } else {
    return value.error("must be a string");
  }
  return ref;
}

Result<std::vector<Information>> decode_information(const Field& root) {
  RONDO_ASSIGN_OR_RETURN(auto items, opt_items(root, "information"));
  std::vector<Information> out;
  for (const Field& i : items) {
    Information info;
    RONDO_ASSIGN_OR_RETURN(info.info_type, req_string(i, "infoType"));
    RONDO_ASSIGN_OR_RETURN(auto refs, opt_items(i, "infoReferences"));
    for (const Field& r : refs) {
      RONDO_ASSIGN_OR_RETURN(ErrorReference ref, decode_reference(r));
      info.info_references.push_back(std::move(ref));
    }
    RONDO_ASSIGN_OR_RETURN(info.info_description, opt_string(i, "infoDescription"));
    RONDO_ASSIGN_OR_RETURN(info.info_level, opt_string(i, "infoLevel"));
    out.push_back(std::move(info));
  }
  return out;
}

Result<std::vector<VehicleError>> decode_errors(const Field& root) {
  RONDO_ASSIGN_OR_RETURN(Field list, root.required("errors"));
  RONDO_ASSIGN_OR_RETURN(auto items, list.items());
  std::vector<VehicleError> out;
  for (const Field& e : items) {
    VehicleError v;
    RONDO_ASSIGN_OR_RETURN(v.error_type, req_string(e, "errorType"));
    RONDO_ASSIGN_OR_RETURN(
        v.error_level,
        parse_enum<ErrorLevel>(e, "errorLevel", {{"WARNING", ErrorLevel::kWarning}, {"FATAL", ErrorLevel::kFatal}}));
    RONDO_ASSIGN_OR_RETURN(v.error_description, opt_string(e, "errorDescription"));
    RONDO_ASSIGN_OR_RETURN(auto refs, opt_items(e, "errorReferences"));
    for (const Field& r : refs) {
      RONDO_ASSIGN_OR_RETURN(ErrorReference ref, decode_reference(r));
      v.error_references.push_back(std::move(ref));
    }
    out.push_back(std::move(v));
  }
  return out;
}

Result<BatteryState> decode_battery(const Field& root) {
  RONDO_ASSIGN_OR_RETURN(Field b, root.required("batteryState"));
  BatteryState s;
  RONDO_ASSIGN_OR_RETURN(s.battery_charge, req_number(b, "batteryCharge"));
  if (s.battery_charge < 0 || s.battery_charge > 100) {
    return b.error_at("batteryCharge", "must be a percentage between 0 and 100");
  }
  RONDO_ASSIGN_OR_RETURN(s.charging, req_bool(b, "charging"));
  if (auto v = b.optional("batteryVoltage")) {
    RONDO_ASSIGN_OR_RETURN(s.battery_voltage, v->as_number());
  }
  return s;
}

Result<std::optional<AgvPosition>> decode_position(const Field& root) {
  auto f = root.optional("agvPosition");
  if (!f) return std::optional<AgvPosition>{};
  AgvPosition p;
  RONDO_ASSIGN_OR_RETURN(p.x, req_number(*f, "x"));
  RONDO_ASSIGN_OR_RETURN(p.y, req_number(*f, "y"));
  RONDO_ASSIGN_OR_RETURN(p.theta, req_number(*f, "theta"));
  RONDO_ASSIGN_OR_RETURN(p.map_id, req_string(*f, "mapId"));
  RONDO_ASSIGN_OR_RETURN(p.position_initialized, req_bool(*f, "positionInitialized"));
  return std::optional<AgvPosition>(std::move(p));
}

Result<State> decode_state_fields(const Field& root) {
  State s;
  RONDO_ASSIGN_OR_RETURN(s.header, decode_header(root));
  RONDO_ASSIGN_OR_RETURN(s.order_id, req_string(root, "orderId"));
  RONDO_ASSIGN_OR_RETURN(s.order_update_id, req_int(root, "orderUpdateId"));
  RONDO_ASSIGN_OR_RETURN(s.last_node_id, req_string(root, "lastNodeId"));
  RONDO_ASSIGN_OR_RETURN(s.last_node_sequence_id, req_int(root, "lastNodeSequenceId"));
  if (s.order_update_id < 0) return root.error_at("orderUpdateId", "must not be negative");
  if (s.last_node_sequence_id < 0) return root.error_at("lastNodeSequenceId", "must not be negative");
  RONDO_ASSIGN_OR_RETURN(s.node_states, decode_node_states(root));
  RONDO_ASSIGN_OR_RETURN(s.edge_states, decode_edge_states(root));
  RONDO_ASSIGN_OR_RETURN(s.driving, req_bool(root, "driving"));
  if (auto v = root.optional("paused")) {
    RONDO_ASSIGN_OR_RETURN(s.paused, v->as_bool());
  }
  if (auto v = root.optional("newBaseRequest")) {
    RONDO_ASSIGN_OR_RETURN(s.new_base_request, v->as_bool());
  }
  if (auto v = root.optional("distanceSinceLastNode")) {
    RONDO_ASSIGN_OR_RETURN(s.distance_since_last_node, v->as_number());
  }
  RONDO_ASSIGN_OR_RETURN(s.operating_mode, parse_enum<OperatingMode>(root, "operatingMode",
                                                                     {{"AUTOMATIC", OperatingMode::kAutomatic},
                                                                      {"SEMIAUTOMATIC", OperatingMode::kSemiautomatic},
                                                                      {"MANUAL", OperatingMode::kManual},
                                                                      {"SERVICE", OperatingMode::kService},
                                                                      {"TEACHIN", OperatingMode::kTeachin}}));
  RONDO_ASSIGN_OR_RETURN(s.action_states, decode_action_states(root));
  RONDO_ASSIGN_OR_RETURN(s.battery_state, decode_battery(root));
  RONDO_ASSIGN_OR_RETURN(s.errors, decode_errors(root));
  RONDO_ASSIGN_OR_RETURN(s.information, decode_information(root));
  RONDO_ASSIGN_OR_RETURN(s.agv_position, decode_position(root));
  return s;
}

}  // namespace

Result<State> decode_state(std::string_view payload) {
  RONDO_ASSIGN_OR_RETURN(Field root, parse_object(payload, "state"));
  return decode_state_fields(root);
}

Result<Connection> decode_connection(std::string_view payload) {
  RONDO_ASSIGN_OR_RETURN(Field root, parse_object(payload, "connection"));
  Connection c;
  RONDO_ASSIGN_OR_RETURN(c.header, decode_header(root));
  RONDO_ASSIGN_OR_RETURN(c.connection_state,
                         parse_enum<ConnectionState>(root, "connectionState",
                                                     {{"ONLINE", ConnectionState::kOnline},
                                                      {"OFFLINE", ConnectionState::kOffline},
                                                      {"CONNECTIONBROKEN", ConnectionState::kConnectionBroken}}));
  return c;
}

Result<Factsheet> decode_factsheet(std::string_view payload, const Compatibility& compat) {
  RONDO_ASSIGN_OR_RETURN(Field root, parse_object(payload, "factsheet"));
  Factsheet f;
  RONDO_ASSIGN_OR_RETURN(f.header, decode_header(root));
  auto type = root.optional("typeSpecification");
  if (!type) {
    if (!compat.vda5050_lib_1_4) {
      return root.error(
          "typeSpecification: missing (a header-only factsheet is accepted only "
          "with the vda5050_lib_1_4 compatibility option)");
    }
    f.header_only = true;
    return f;
  }
  RONDO_ASSIGN_OR_RETURN(f.series_name, req_string(*type, "seriesName"));
  if (auto phys = root.optional("physicalParameters")) {
    if (auto v = phys->optional("speedMax")) {
      RONDO_ASSIGN_OR_RETURN(f.max_speed, v->as_number());
    }
  }
  if (auto features = root.optional("protocolFeatures")) {
    RONDO_ASSIGN_OR_RETURN(auto actions, opt_items(*features, "agvActions"));
    for (const Field& a : actions) {
      RONDO_ASSIGN_OR_RETURN(std::string action_type, req_string(a, "actionType"));
      if (action_type.empty()) return a.error_at("actionType", "must not be empty");
      if (std::find(f.agv_actions.begin(), f.agv_actions.end(), action_type) == f.agv_actions.end())
        f.agv_actions.push_back(std::move(action_type));
    }
  }
  return f;
}

Result<Header> decode_header_only(std::string_view payload, std::string_view topic) {
  RONDO_ASSIGN_OR_RETURN(Field root, parse_object(payload, topic));
  return decode_header(root);
}

}  // namespace rondo::vda5050
