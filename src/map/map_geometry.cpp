#include "rondo/map/map_geometry.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace rondo::map {
namespace {

bool contains_ignoring_case(std::string_view text, std::string_view word) {
  auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  auto it = std::search(text.begin(), text.end(), word.begin(), word.end(),
                        [&](char a, char b) { return lower(a) == lower(b); });
  return it != text.end();
}

}  // namespace

ActionKind action_kind(std::string_view action) {
  if (contains_ignoring_case(action, "door")) return ActionKind::kDoor;
  if (contains_ignoring_case(action, "dock")) return ActionKind::kDocking;
  return ActionKind::kMove;
}

const char* to_string(ActionKind kind) {
  switch (kind) {
    case ActionKind::kMove:
      return "move";
    case ActionKind::kDoor:
      return "door";
    case ActionKind::kDocking:
      return "docking";
  }
  return "move";
}

double edge_length(const TopoMap& map, EdgeIndex edge) {
  const Pose& a = map.node(map.from_index(edge)).pose;
  const Pose& b = map.node(map.to_index(edge)).pose;
  return std::hypot(b.x - a.x, b.y - a.y);
}

namespace {

std::vector<double> dijkstra(const TopoMap& map, NodeIndex from, bool towards) {
  std::vector<double> best(map.node_count(), std::numeric_limits<double>::infinity());
  using Item = std::pair<double, NodeIndex>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  best.at(from) = 0;
  open.emplace(0.0, from);
  while (!open.empty()) {
    const auto [d, n] = open.top();
    open.pop();
    if (d > best[n]) continue;
    for (const EdgeIndex e : towards ? map.in_edges(n) : map.out_edges(n)) {
      const NodeIndex to = towards ? map.from_index(e) : map.to_index(e);
      const double via = d + edge_length(map, e);
      if (via < best[to]) best[to] = via, open.emplace(via, to);
    }
  }
  return best;
}

}  // namespace

std::vector<double> shortest_metres(const TopoMap& map, NodeIndex from) { return dijkstra(map, from, false); }
std::vector<double> shortest_metres_to(const TopoMap& map, NodeIndex to) { return dijkstra(map, to, true); }

Duration nominal_travel_time(const TopoMap& map, EdgeIndex edge, const TravelTimeOptions& options) {
  const Edge& e = map.edge(edge);
  double speed = e.top_speed.value_or(options.default_speed);
  if (!(speed > 0) || !std::isfinite(speed)) speed = TravelTimeOptions{}.default_speed;
  double seconds = edge_length(map, edge) / speed;
  switch (action_kind(e.action)) {
    case ActionKind::kDoor:
      seconds += options.door_overhead_s;
      break;
    case ActionKind::kDocking:
      seconds += options.docking_overhead_s;
      break;
    case ActionKind::kMove:
      break;
  }
  // Poses are finite, but two far-apart ones over a tiny speed could still overflow a Duration.
  constexpr double kLongest = 1.0e12;  // seconds, about 31,700 years
  return from_seconds(std::clamp(seconds, 0.0, kLongest));
}

std::optional<BoundingBox> bounding_box(const TopoMap& map) {
  if (map.node_count() == 0) return std::nullopt;
  const Pose& first = map.node(0).pose;
  BoundingBox box{first.x, first.y, first.x, first.y};
  for (const Node& n : map.nodes()) {
    box.min_x = std::min(box.min_x, n.pose.x);
    box.min_y = std::min(box.min_y, n.pose.y);
    box.max_x = std::max(box.max_x, n.pose.x);
    box.max_y = std::max(box.max_y, n.pose.y);
  }
  return box;
}

}  // namespace rondo::map
