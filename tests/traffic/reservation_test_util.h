// Small maps for the reservation tests: places with capacities, passages both ways with a mark,
// and a listener that counts what it was told.
#pragma once

#include <string>
#include <tuple>
#include <vector>

#include "rondo/map/topo_map.h"
#include "rondo/traffic/reservations.h"

namespace rondo::traffic::testing {

struct Place {
  std::string name;
  int capacity = 1;
};

// Both directions of each passage (from, to, mark), with ids "<from>_<to>"; nodes on a line.
inline map::TopoMap reservation_map(const std::vector<Place>& places,
                                    const std::vector<std::tuple<std::string, std::string, map::Narrow>>& passages) {
  std::vector<map::Node> nodes;
  double x = 0;
  for (const Place& p : places) nodes.push_back({.name = p.name, .pose = {x += 5, 0, 0}, .capacity = p.capacity});
  std::vector<map::Edge> edges;
  for (const auto& [a, b, mark] : passages) {
    edges.push_back({.id = a + "_" + b, .from = a, .to = b, .action = "move_base", .narrow = mark});
    edges.push_back({.id = b + "_" + a, .from = b, .to = a, .action = "move_base", .narrow = mark});
  }
  return map::TopoMap::build("reservations", std::move(nodes), std::move(edges)).value();
}

class Told final : public ReservationListener {
 public:
  void on_way_may_be_clear() override { ++clear; }
  void on_make_way(const MakeWay& m) override { make_way.push_back(m); }
  int clear = 0;
  std::vector<MakeWay> make_way;
};

}  // namespace rondo::traffic::testing
