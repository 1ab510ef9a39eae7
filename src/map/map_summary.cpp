#include "rondo/map/map_summary.h"

#include <algorithm>

#include "rondo/map/map_validation.h"

namespace rondo::map {

MapSummary summarize(const TopoMap& map) {
  MapSummary s;
  s.name = map.name();
  s.nodes = map.node_count();
  s.edges = map.edge_count();
  s.bounding_box = bounding_box(map);
  for (EdgeIndex e = 0; e < map.edge_count(); ++e) {
    const Edge& edge = map.edge(e);
    ++s.actions[edge.action];
    const double length = edge_length(map, e);
    s.total_edge_length += length;
    if (s.longest_edge.empty() || length > s.longest_edge_length) {
      s.longest_edge_length = length;
      s.longest_edge = edge.id;
    }
    if (edge.top_speed) ++s.edges_with_top_speed;
    if (edge.narrow == Narrow::kSingle) ++s.narrow_single;
    if (edge.narrow == Narrow::kOneWay) ++s.narrow_one_way;
    s.nominal_travel_time_total += to_seconds(nominal_travel_time(map, e));
    if (edge.door) {
      auto it = std::find_if(s.doors.begin(), s.doors.end(), [&](const DoorSummary& d) { return d.id == *edge.door; });
      if (it == s.doors.end()) it = s.doors.insert(s.doors.end(), DoorSummary{*edge.door, {}});
      it->edges.push_back(edge.id);
    }
  }
  for (const Node& n : map.nodes()) {
    if (!n.influence.empty()) ++s.nodes_with_influence;
    if (n.capacity > 1) ++s.nodes_with_capacity;
    s.largest_capacity = std::max(s.largest_capacity, n.capacity);
  }
  s.strongly_connected_components = strongly_connected_components(map).size();
  s.warnings = map_warnings(map);
  return s;
}

Json to_json(const MapSummary& s) {
  Json j = Json::object();
  j["name"] = s.name;
  j["nodes"] = s.nodes;
  j["edges"] = s.edges;
  Json actions = Json::object();
  for (const auto& [action, count] : s.actions) actions[action] = count;
  j["actions"] = std::move(actions);
  Json doors = Json::array();
  for (const DoorSummary& d : s.doors) doors.push_back(Json{{"id", d.id}, {"edges", d.edges}});
  j["doors"] = std::move(doors);
  if (s.bounding_box) {
    const BoundingBox& b = *s.bounding_box;
    j["bounding_box_m"] = Json{{"min_x", b.min_x}, {"min_y", b.min_y}, {"max_x", b.max_x}, {"max_y", b.max_y}};
  } else {
    j["bounding_box_m"] = nullptr;
  }
  j["total_edge_length_m"] = s.total_edge_length;
  j["longest_edge"] =
      s.longest_edge.empty() ? Json(nullptr) : Json{{"id", s.longest_edge}, {"length_m", s.longest_edge_length}};
  j["edges_with_top_speed"] = s.edges_with_top_speed;
  j["nodes_with_influence"] = s.nodes_with_influence;
  j["nodes_with_capacity"] = s.nodes_with_capacity;
  j["largest_capacity"] = s.largest_capacity;
  j["narrow_edges"] = Json{{"single", s.narrow_single}, {"one_way", s.narrow_one_way}};
  j["strongly_connected"] = s.strongly_connected_components <= 1;
  j["strongly_connected_components"] = s.strongly_connected_components;
  j["nominal_travel_time_total_s"] = s.nominal_travel_time_total;
  j["warnings"] = s.warnings;
  return j;
}

}  // namespace rondo::map
