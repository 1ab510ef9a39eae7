// The VDA 5050 2.0.0 messages between master control (rondo) and a vehicle, as typed values.
// Field names follow the specification (../shared/data/vda5050/2.0.0/VDA5050_EN.md) in
// snake_case. What rondo sends (Order, InstantActions) is encoded by encode.h; what a vehicle
// sends (State, Connection, Factsheet) is decoded defensively by decode.h.
//
//   Order o;
//   o.order_id = "nav-17";
//   o.nodes.push_back({.node_id = "WayPoint1", .sequence_id = 0, .released = true,
//                      .position = NodePosition{.x = 1, .y = 2, .theta = 0, .map_id = "g4s"}});
//
// Units are SI (metres, radians, m/s); angles are in [-pi, pi].
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rondo/core/time.h"

namespace rondo::vda5050 {

inline constexpr const char* kProtocolVersion = "2.0.0";

// The common header of every message. header_id counts per topic and sender.
struct Header {
  std::int64_t header_id = 0;
  Time timestamp{};
  std::string version = kProtocolVersion;
  std::string manufacturer;
  std::string serial_number;
  bool operator==(const Header&) const = default;
};

enum class BlockingType { kNone, kSoft, kHard };

// A parameter's value: the schema allows a string, a number, a boolean or an array; rondo's
// task arguments are strings, so only the scalar kinds are modelled.
using ParameterValue = std::variant<std::string, double, bool>;

struct ActionParameter {
  std::string key;
  ParameterValue value;
  bool operator==(const ActionParameter&) const = default;
};

struct Action {
  std::string action_type;  // e.g. "pick", "cancelOrder", or a task action's name
  std::string action_id;    // unique within the order (instant actions: unique per vehicle)
  BlockingType blocking_type = BlockingType::kHard;
  std::string action_description;  // optional; empty is not sent
  std::vector<ActionParameter> action_parameters;
  bool operator==(const Action&) const = default;
};

struct NodePosition {
  double x = 0;
  double y = 0;
  std::optional<double> theta;         // absent: the vehicle may choose its heading
  double allowed_deviation_xy = 0;     // metres; 0 is the vehicle's own tolerance
  double allowed_deviation_theta = 0;  // radians
  std::string map_id;
  bool operator==(const NodePosition&) const = default;
};

struct OrderNode {
  std::string node_id;
  std::int64_t sequence_id = 0;  // even: nodes, odd: edges, increasing along the order
  bool released = false;         // true: base, false: horizon
  std::optional<NodePosition> position;
  std::vector<Action> actions;
  bool operator==(const OrderNode&) const = default;
};

struct OrderEdge {
  std::string edge_id;
  std::int64_t sequence_id = 0;
  bool released = false;
  std::string start_node_id;
  std::string end_node_id;
  std::optional<double> max_speed;  // m/s
  std::optional<double> length;     // metres
  std::vector<Action> actions;
  bool operator==(const OrderEdge&) const = default;
};

// An order or an order update (same order_id, a higher order_update_id).
struct Order {
  std::string order_id;
  std::int64_t order_update_id = 0;
  std::vector<OrderNode> nodes;  // nodes[i] and nodes[i+1] are joined by edges[i]
  std::vector<OrderEdge> edges;
  bool operator==(const Order&) const = default;
};

struct InstantActions {
  std::vector<Action> actions;
  bool operator==(const InstantActions&) const = default;
};

// ---- from the vehicle ----

enum class ActionStatus { kWaiting, kInitializing, kRunning, kPaused, kFinished, kFailed };
enum class ErrorLevel { kWarning, kFatal };
enum class OperatingMode { kAutomatic, kSemiautomatic, kManual, kService, kTeachin };
enum class ConnectionState { kOnline, kOffline, kConnectionBroken };

struct NodeState {
  std::string node_id;
  std::int64_t sequence_id = 0;
  bool released = false;
  bool operator==(const NodeState&) const = default;
};

struct EdgeState {
  std::string edge_id;
  std::int64_t sequence_id = 0;
  bool released = false;
  bool operator==(const EdgeState&) const = default;
};

struct ActionState {
  std::string action_id;
  std::string action_type;  // optional in the schema; empty when absent
  ActionStatus action_status = ActionStatus::kWaiting;
  std::string result_description;
  bool operator==(const ActionState&) const = default;
};

struct ErrorReference {
  std::string reference_key;
  std::string reference_value;
  bool operator==(const ErrorReference&) const = default;
};

struct VehicleError {
  std::string error_type;  // e.g. "orderError", "validationError", "noRouteError"
  ErrorLevel error_level = ErrorLevel::kWarning;
  std::string error_description;
  std::vector<ErrorReference> error_references;
  bool operator==(const VehicleError&) const = default;
};

// An entry of the state's information[]: what the vehicle wants known, in its vendor's words.
// Which of them are observations is the deployment's (information.h).
struct Information {
  std::string info_type{};                        // infoType, the vendor's name
  std::vector<ErrorReference> info_references{};  // infoReferences (the same key/value pairs as errors)
  std::string info_description{};                 // "" when absent
  std::string info_level{};                       // INFO or DEBUG ("" when absent)
  bool operator==(const Information&) const = default;
};

struct BatteryState {
  double battery_charge = 0;  // percent, 0..100
  bool charging = false;
  std::optional<double> battery_voltage;
  bool operator==(const BatteryState&) const = default;
};

struct AgvPosition {
  double x = 0;
  double y = 0;
  double theta = 0;
  std::string map_id;
  bool position_initialized = false;
  bool operator==(const AgvPosition&) const = default;
};

struct State {
  Header header;
  std::string order_id;  // "" when the vehicle has no order
  std::int64_t order_update_id = 0;
  std::string last_node_id;  // "" before the first node
  std::int64_t last_node_sequence_id = 0;
  std::vector<NodeState> node_states;  // nodes still to be traversed
  std::vector<EdgeState> edge_states;  // edges still to be traversed
  bool driving = false;
  bool paused = false;
  bool new_base_request = false;
  std::optional<double> distance_since_last_node;
  OperatingMode operating_mode = OperatingMode::kAutomatic;
  std::vector<ActionState> action_states;
  BatteryState battery_state;
  std::vector<VehicleError> errors;
  std::vector<Information> information;  // optional in what rondo reads (required by the schema)
  std::optional<AgvPosition> agv_position;
  bool operator==(const State&) const = default;
};

struct Connection {
  Header header;
  ConnectionState connection_state = ConnectionState::kOffline;
  bool operator==(const Connection&) const = default;
};

// What rondo reads of a factsheet: the header always, the type specification when it is there,
// and the actions the vehicle runs when it lists them.
struct Factsheet {
  Header header;
  bool header_only = false;         // only the header came (vda-5050-lib 1.4.0 sends this)
  std::string series_name;          // typeSpecification.seriesName
  std::optional<double> max_speed;  // physicalParameters.speedMax, m/s
  // protocolFeatures.agvActions[].actionType, in order, without repeats; empty when none is listed
  std::vector<std::string> agv_actions;
  bool operator==(const Factsheet&) const = default;
};

const char* to_string(BlockingType t);
const char* to_string(ActionStatus s);
const char* to_string(ErrorLevel l);
const char* to_string(OperatingMode m);
const char* to_string(ConnectionState c);

}  // namespace rondo::vda5050
