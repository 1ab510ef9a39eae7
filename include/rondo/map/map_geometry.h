// Geometry of a topological map and the distance-based travel-time estimate: the prior that the
// learned models start from before any traversal has been seen (the paper's W0 model).
//
//   double metres = edge_length(map, e);
//   Duration t = nominal_travel_time(map, e);                 // length / speed + action overhead
//   Duration slow = nominal_travel_time(map, e, {.default_speed = 0.3});
//
// Speed is the edge's top speed when it has one, else TravelTimeOptions::default_speed. Some
// behaviours cost time beyond the distance; the overhead is added per edge, by the kind of action:
//   door    (the action name contains "door", any case: doorPassing, door_wait_and_pass): 15 s
//           for checking that the door is open, slowing down, and waiting at the door;
//   docking (the action name contains "dock", any case: docking, undocking): 30 s for aligning
//           with the charger and the slow final approach or reversing out;
//   move    (everything else: move_base, human_aware_navigation...): 0 s.
#pragma once

#include <string_view>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"

namespace rondo::map {

enum class ActionKind { kMove, kDoor, kDocking };

// How an action name is classified, as described above.
ActionKind action_kind(std::string_view action);
const char* to_string(ActionKind kind);

struct TravelTimeOptions {
  double default_speed = 0.5;        // m/s, for edges without a top speed; must be > 0
  double door_overhead_s = 15.0;     // seconds added to door edges
  double docking_overhead_s = 30.0;  // seconds added to docking and undocking edges
};

// The straight-line distance between the edge's two node positions, in metres.
double edge_length(const TopoMap& map, EdgeIndex edge);

// The no-data estimate of crossing `edge`: edge_length / speed + the overhead of its action kind.
// Precondition: options.default_speed > 0 (a non-positive speed is treated as 0.5 m/s).
Duration nominal_travel_time(const TopoMap& map, EdgeIndex edge, const TravelTimeOptions& options = {});

// The shortest distance along edges from `from` to every node, in metres (edge_length summed;
// infinity where no way leads). Dijkstra, O(E log V).
std::vector<double> shortest_metres(const TopoMap& map, NodeIndex from);
// The same towards `to`: from every node to it.
std::vector<double> shortest_metres_to(const TopoMap& map, NodeIndex to);

// The axis-aligned box around all node positions.
struct BoundingBox {
  double min_x = 0;
  double min_y = 0;
  double max_x = 0;
  double max_y = 0;
  bool operator==(const BoundingBox&) const = default;
};
// Nothing for a map without nodes.
std::optional<BoundingBox> bounding_box(const TopoMap& map);

}  // namespace rondo::map
