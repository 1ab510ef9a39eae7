// Orders from routes on the topological map: a navigation is one order, whose *base* (released)
// is the part the executor commits to and whose *horizon* (not released) is the rest of the
// expected route. After each decision point the base is extended, and the horizon replaced when
// the route changes, by an order update stitched at the last base node.
//
//   RouteSpec spec{.route = {a, b, c, d}, .base_edges = 1, .map_id = "g4s", .final_actions = task.actions};
//   Result<Order> o = build_order(map, "nav-17", spec);       // a-b released, b-c-d horizon
//   spec = {.route = {b, c, d}, .base_edges = 1, .map_id = "g4s", .final_actions = task.actions};
//   Result<Order> u = build_update(map, *o, spec);            // orderUpdateId 1, starts at b (seq 2)
//
// Node i of an order has sequenceId s0 + 2i and the edge after it s0 + 2i + 1, where s0 is 0 for a
// new order and the stitch node's sequenceId for an update. Nodes carry their map pose as
// nodePosition (theta = yaw, the goal tolerances as allowed deviations, the deployment's mapId);
// edges carry the map edge's id, maxSpeed (its top speed) and length. The task's actions go on
// the final node with blockingType HARD and their arguments as actionParameters (see
// to_parameter_value). Pure functions: no clock, no I/O.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/task.h"
#include "rondo/map/topo_map.h"
#include "rondo/vda5050/messages.h"

namespace rondo::vda5050 {

struct RouteSpec {
  std::vector<map::NodeIndex> route;         // consecutive nodes joined by map edges; at least one node
  std::size_t base_edges = 0;                // how many of the route's edges are released (<= edges)
  std::string map_id;                        // the deployment's VDA 5050 mapId
  std::vector<rondo::Action> final_actions;  // run at the last node of the route
};

// A new order (orderUpdateId 0). Errors: an empty route, a node index outside the map, two
// consecutive nodes without a map edge between them, base_edges beyond the route's edges.
Result<Order> build_order(const map::TopoMap& map, const std::string& order_id, const RouteSpec& spec);

// The update of `previous`: same orderId, orderUpdateId + 1, and spec.route[0] must be the last
// base node of `previous`, which it repeats with the same sequenceId (released). Everything after
// it, horizon included, is replaced by spec's route.
Result<Order> build_update(const map::TopoMap& map, const Order& previous, const RouteSpec& spec);

// The last released node of an order (the decision point where the next update is stitched).
// Precondition: order.nodes is not empty and nodes[0] is released (as built above).
const OrderNode& last_base_node(const Order& order);

// A task argument as a typed VDA 5050 value: "true"/"false" become booleans, a plain decimal
// number ("2", "-0.5", "1e3") a number, anything else stays a string.
ParameterValue to_parameter_value(const std::string& text);

}  // namespace rondo::vda5050
