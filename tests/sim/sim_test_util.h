// Shared pieces of the sim tests: a small map with a door and a dock, the real maps, fixed times.
#pragma once

#include <gtest/gtest.h>

#include "rondo/core/time.h"
#include "rondo/core/timezone.h"
#include "rondo/map/map_loader.h"
#include "rondo/map/topo_map.h"

namespace rondo::sim::testing {

// Dock -- Hall -- Office, and Hall -- Kitchen through door "kd". Corridors are 10 m long.
inline map::TopoMap small_map() {
  std::vector<map::Node> nodes = {{.name = "Dock", .pose = {0, 0, 0}},
                                  {.name = "Hall", .pose = {10, 0, 0}},
                                  {.name = "Office", .pose = {20, 0, 0}},
                                  {.name = "Kitchen", .pose = {10, 10, 0}}};
  std::vector<map::Edge> edges = {
      {.id = "Dock_Hall", .from = "Dock", .to = "Hall", .action = "undocking"},
      {.id = "Hall_Dock", .from = "Hall", .to = "Dock", .action = "docking"},
      {.id = "Hall_Office", .from = "Hall", .to = "Office", .action = "move_base"},
      {.id = "Office_Hall", .from = "Office", .to = "Hall", .action = "move_base"},
      {.id = "Hall_Kitchen", .from = "Hall", .to = "Kitchen", .action = "doorPassing", .door = "kd"},
      {.id = "Kitchen_Hall", .from = "Kitchen", .to = "Hall", .action = "doorPassing", .door = "kd"},
  };
  return map::TopoMap::build("small", std::move(nodes), std::move(edges)).value();
}

inline const map::TopoMap& g4s_map() {
  static const map::TopoMap m = map::load_map("../shared/data/maps/g4s_y2.tmap").value();
  return m;
}

inline const map::TopoMap& witham_map() {
  static const map::TopoMap m = map::load_map("examples/witham/map.yaml").value();
  return m;
}

inline TimeZone london() { return TimeZone::named("Europe/London").value(); }

// Local times in London (winter: UTC+0). 2026-11-23 is a Monday.
inline Time local(const char* text) { return london().parse_time(text).value(); }

inline map::EdgeIndex edge(const map::TopoMap& m, const char* id) { return m.find_edge(id).value(); }
inline map::NodeIndex node(const map::TopoMap& m, const char* name) { return m.find_node(name).value(); }

}  // namespace rondo::sim::testing
