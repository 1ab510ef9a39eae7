// The assumptions of a schedule (rondo/exec/assumption.h), worked out on the map: a task needs the
// doors on the way from the dock to its places (the rooms it enters) and the edges of the shortest
// way from the previous stop of the plan to its places.
//
//   AssumptionMap where(map, dock);
//   std::vector<Assumption> a = where.for_plan(robot_location, stops);
//   std::string text = describe(a, zone);  // "letter-drop: door A-120-door open, 7 edges passable, until 10:12"
#pragma once

#include <map>
#include <string>
#include <vector>

#include "rondo/core/timezone.h"
#include "rondo/exec/assumption.h"
#include "rondo/map/topo_map.h"

namespace rondo::exec {

// One task of the plan, in the order it is to run.
struct PlannedStop {
  TaskId task;
  map::NodeIndex start = 0;
  map::NodeIndex end = 0;
  Time until{};
};

class AssumptionMap {
 public:
  // Precondition: `dock` is a node of `map`; the map outlives this.
  AssumptionMap(const map::TopoMap& map, map::NodeIndex dock);

  // The doors crossed by the shortest way from the dock to `node` (the rooms `node` is in).
  const std::vector<std::string>& doors_to(map::NodeIndex node) const { return doors_to_.at(node); }
  // The edges of the shortest way (by length) from `from` to `to`; empty when there is none.
  std::vector<map::EdgeIndex> route(map::NodeIndex from, map::NodeIndex to) const;
  // Every assumption of a plan that starts at `here`: per stop its doors (once per task) and the
  // edges of its way there and on to its end place.
  std::vector<Assumption> for_plan(map::NodeIndex here, const std::vector<PlannedStop>& stops) const;

 private:
  // Shortest-path tree from `source`: the edge that reaches each node (or none).
  const std::vector<std::ptrdiff_t>& tree(map::NodeIndex source) const;

  const map::TopoMap& map_;
  std::vector<std::vector<std::string>> doors_to_;
  mutable std::map<map::NodeIndex, std::vector<std::ptrdiff_t>> trees_;
};

// The doors a schedule assumes open, per task, and how many edges it assumes passable, for the
// event log: "letter-drop: door A-120-door open until 10:12, 6 edges passable; book-drop: ...".
// Empty when `assumptions` is.
std::string describe(const std::vector<Assumption>& assumptions, const TimeZone& zone);

}  // namespace rondo::exec
