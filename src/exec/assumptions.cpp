#include "assumptions.h"

#include <fmt/format.h>

#include <algorithm>
#include <functional>
#include <limits>
#include <queue>
#include <set>
#include <utility>

#include "rondo/map/map_geometry.h"

namespace rondo::exec {

const char* to_string(Assumption::Kind kind) {
  switch (kind) {
    case Assumption::Kind::kDoorOpen: return "door open";
    case Assumption::Kind::kEdgePassable: return "edge passable";
  }
  return "door open";
}

AssumptionMap::AssumptionMap(const map::TopoMap& map, map::NodeIndex dock) : map_(map) {
  doors_to_.resize(map.node_count());
  const std::vector<std::ptrdiff_t>& from_dock = tree(dock);
  for (map::NodeIndex n = 0; n < map.node_count(); ++n) {
    std::vector<std::string> doors;
    for (map::NodeIndex at = n; from_dock[at] >= 0;) {
      const auto e = static_cast<map::EdgeIndex>(from_dock[at]);
      if (const auto& door = map.edge(e).door; door && std::find(doors.begin(), doors.end(), *door) == doors.end())
        doors.push_back(*door);
      at = map.from_index(e);
    }
    std::reverse(doors.begin(), doors.end());
    doors_to_[n] = std::move(doors);
  }
}

const std::vector<std::ptrdiff_t>& AssumptionMap::tree(map::NodeIndex source) const {
  if (const auto it = trees_.find(source); it != trees_.end()) return it->second;
  std::vector<double> dist(map_.node_count(), std::numeric_limits<double>::infinity());
  std::vector<std::ptrdiff_t> via(map_.node_count(), -1);
  using Item = std::pair<double, map::NodeIndex>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[source] = 0;
  open.push({0.0, source});
  while (!open.empty()) {
    const auto [d, n] = open.top();
    open.pop();
    if (d > dist[n]) continue;
    for (map::EdgeIndex e : map_.out_edges(n)) {
      const map::NodeIndex to = map_.to_index(e);
      const double nd = d + map::edge_length(map_, e);
      if (nd < dist[to]) {  // ties keep the first edge in map order: the same tree on every run
        dist[to] = nd;
        via[to] = static_cast<std::ptrdiff_t>(e);
        open.push({nd, to});
      }
    }
  }
  return trees_.emplace(source, std::move(via)).first->second;
}

std::vector<map::EdgeIndex> AssumptionMap::route(map::NodeIndex from, map::NodeIndex to) const {
  const std::vector<std::ptrdiff_t>& via = tree(from);
  std::vector<map::EdgeIndex> edges;
  for (map::NodeIndex at = to; at != from;) {
    if (via[at] < 0) return {};
    const auto e = static_cast<map::EdgeIndex>(via[at]);
    edges.push_back(e);
    at = map_.from_index(e);
  }
  std::reverse(edges.begin(), edges.end());
  return edges;
}

std::vector<Assumption> AssumptionMap::for_plan(map::NodeIndex here, const std::vector<PlannedStop>& stops) const {
  std::vector<Assumption> out;
  for (const PlannedStop& s : stops) {
    std::set<std::string> doors;
    for (map::NodeIndex n : {s.start, s.end})
      for (const std::string& door : doors_to(n))
        if (doors.insert(door).second)
          out.push_back({.kind = Assumption::Kind::kDoorOpen, .what = door, .task = s.task, .until = s.until});
    std::vector<map::EdgeIndex> way = route(here, s.start);
    const std::vector<map::EdgeIndex> on = route(s.start, s.end);
    way.insert(way.end(), on.begin(), on.end());
    for (map::EdgeIndex e : way)
      out.push_back({.kind = Assumption::Kind::kEdgePassable, .what = map_.edge(e).id, .task = s.task,
                     .until = s.until});
    here = s.end;
  }
  return out;
}

std::string describe(const std::vector<Assumption>& assumptions, const TimeZone& zone) {
  std::string text;
  for (std::size_t i = 0; i < assumptions.size();) {
    const TaskId& task = assumptions[i].task;
    std::vector<std::string> doors;
    int edges = 0;
    const Time until = assumptions[i].until;
    for (; i < assumptions.size() && assumptions[i].task == task; ++i) {
      if (assumptions[i].kind == Assumption::Kind::kDoorOpen)
        doors.push_back(assumptions[i].what);
      else
        ++edges;
    }
    std::string part = task + ": ";
    for (const std::string& d : doors) part += fmt::format("door {} open, ", d);
    part += fmt::format("{} edge{} passable, until {}", edges, edges == 1 ? "" : "s", zone.format_clock(until));
    text += (text.empty() ? "" : "; ") + part;
  }
  return text;
}

}  // namespace rondo::exec
