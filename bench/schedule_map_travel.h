// For the scheduler benches: the expected travel seconds between the places of a real map under
// its distance prior (plan::TravelPlanner over plan::DistancePrior: shortest nominal travel times),
// as a static matrix the scheduler and CBC both read.
//
//   auto g4s = map_travel("../shared/data/maps/g4s_y2.tmap", "ChargingPoint", Time{} + hours(8));
//   Problem day = testing::robot_day(g4s->travel, {.tasks = 15, .dock = g4s->dock});
//
// Only places that the dock reaches and that reach the dock are kept (index = position in names).
#pragma once

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "rondo/map/map_loader.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/schedule/travel_oracle.h"

namespace rondo::bench {

struct MapMatrix {
  std::shared_ptr<const schedule::MatrixTravel> travel;
  std::vector<std::string> names;
  schedule::LocationIndex dock = 0;
};

inline Result<MapMatrix> map_travel(const std::string& file, const std::string& dock_name, Time at) {
  auto loaded = map::load_map(file);
  if (!loaded) return loaded.error();
  const map::TopoMap& m = *loaded;
  auto dock = m.find_node(dock_name);
  if (!dock) return Error::not_found(file + ": no node '" + dock_name + "'");
  plan::TravelPlanner oracle(m, std::make_shared<plan::DistancePrior>(m));
  std::vector<map::NodeIndex> kept;
  for (map::NodeIndex v = 0; v < m.node_count(); ++v)
    if (std::isfinite(oracle.expected_seconds(*dock, v, at)) && std::isfinite(oracle.expected_seconds(v, *dock, at)))
      kept.push_back(v);
  MapMatrix out;
  std::vector<Duration> matrix;
  for (map::NodeIndex a : kept) {
    out.names.push_back(m.node(a).name);
    if (a == *dock) out.dock = out.names.size() - 1;
    for (map::NodeIndex b : kept) matrix.push_back(from_seconds(oracle.expected_seconds(a, b, at)));
  }
  auto travel = schedule::MatrixTravel::create(kept.size(), std::move(matrix));
  if (!travel) return travel.error();
  out.travel = std::make_shared<schedule::MatrixTravel>(std::move(*travel));
  return out;
}

}  // namespace rondo::bench
