// Hand-made maps for the planner's table-driven tests: a map from node names and "A>B" edges.
//
//   map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "B>C"});
//   Mdp mdp = outcomes_mdp(m, {{1.0, 10.0}, {0.5, 4.0}});
#pragma once

#include <string>
#include <vector>

#include "rondo/map/topo_map.h"
#include "rondo/plan/mdp.h"

namespace rondo::plan::testing {

inline map::TopoMap small_map(const std::vector<std::string>& names, const std::vector<std::string>& arrows) {
  std::vector<map::Node> nodes;
  double x = 0;
  for (const auto& n : names) nodes.push_back({.name = n, .pose = {x++, 0, 0}});
  std::vector<map::Edge> edges;
  for (const auto& a : arrows) {
    const auto cut = a.find('>');
    const std::string from = a.substr(0, cut);
    const std::string to = a.substr(cut + 1);
    edges.push_back({.id = from + "_" + to, .from = from, .to = to, .action = "move_base"});
  }
  return map::TopoMap::build("small", std::move(nodes), std::move(edges)).value();
}

inline Mdp outcomes_mdp(const map::TopoMap& m, std::vector<EdgeCrossing> outcomes) {
  return Mdp::from_outcomes(m, std::move(outcomes), Time{}).value();
}

}  // namespace rondo::plan::testing
