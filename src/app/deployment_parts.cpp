#include "deployment_parts.h"

#include <fmt/format.h>

#include "rondo/map/map_loader.h"

namespace rondo::app {

Result<DeploymentParts> load_parts(const Deployment& d) {
  RONDO_ASSIGN_OR_RETURN(map::TopoMap map, map::load_map(d.map));
  const std::optional<map::NodeIndex> dock = map.find_node(d.dock);
  if (!dock) {
    return Error::invalid(fmt::format("{}: node '{}' is not on the map '{}' ({})", d.dock_where, d.dock, map.name(),
                                      d.map.string()));
  }
  if (!d.executor.return_to.empty() && !map.find_node(d.executor.return_to))
    return Error::invalid(fmt::format("{}: executor.return_to: node '{}' is not on the map '{}'", d.file.string(),
                                      d.executor.return_to, map.name()));
  TaskFile plan;
  if (d.routines) {
    const PlaceCheck places{.known = [&map](std::string_view node) { return map.find_node(node).has_value(); },
                            .map_name = map.name()};
    RONDO_ASSIGN_OR_RETURN(plan, load_task_file(*d.routines, &places));
  }
  // The world and the requests decoders check their nodes against the map themselves.
  std::optional<sim::SimWorld> world;
  if (d.world) {
    RONDO_ASSIGN_OR_RETURN(world, sim::load_world(*d.world, map, d.zone));
    if (d.battery) world->battery = *d.battery;  // the deployment's battery replaces the world's
  }
  std::optional<sim::RequestGenerator> people;
  if (d.requests) { RONDO_ASSIGN_OR_RETURN(people, sim::RequestGenerator::load(*d.requests, map, d.zone)); }
  std::optional<lang::Places> places;
  if (d.places) { RONDO_ASSIGN_OR_RETURN(places, lang::Places::load(*d.places, map)); }
  return DeploymentParts{std::move(map), *dock, std::move(plan), std::move(world), std::move(people), std::move(places)};
}

}  // namespace rondo::app
