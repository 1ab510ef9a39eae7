#include "robot_factory.h"

#include <fmt/format.h>

#include "rondo/fleet/balanced_allocator.h"
#include "rondo/fleet/fleet_scheduler_allocator.h"
#include "rondo/sim/sim_robot.h"
#include "rondo/vda5050/vda5050_robot.h"

namespace rondo::app {
namespace {

std::size_t simulated_robots(const Deployment& d) {
  std::size_t n = 0;
  for (const RobotSpec& r : d.robots)
    if (!r.vda5050) ++n;
  return n;
}

// The building's traffic: the map's capacities, a listed dock's room where it is larger.
std::unique_ptr<sim::Traffic> make_traffic(const Deployment& d, const DeploymentParts& parts) {
  auto traffic = std::make_unique<sim::Traffic>(parts.map, parts.world->traffic);
  for (const DockSpec& dock : d.docks)
    if (const auto n = parts.map.find_node(dock.node)) traffic->set_capacity(*n, node_room(d, parts.map, *n));
  return traffic;
}

}  // namespace

Result<DeploymentRobot> make_robot(const Deployment& d, const RobotSpec& spec, DeploymentParts& parts,
                                   exec::Clock& clock, map::NodeIndex start, std::uint64_t seed) {
  if (spec.vda5050) {
    RONDO_ASSIGN_OR_RETURN(std::unique_ptr<vda5050::Vda5050Robot> vehicle,
                           vda5050::Vda5050Robot::create(clock, parts.map, *spec.vda5050, {.start = start}));
    return DeploymentRobot{.robot = std::move(vehicle), .charging_time = [] { return Duration{0}; }};
  }
  // load_deployment gives the simulated robot a world, always.
  if (!parts.world) return Error::internal(fmt::format("{}: the simulated robot has no world", d.file.string()));
  parts.world->edges->set_seed(d.seed);  // the building's own spells: the deployment's seed, also on resume
  const std::size_t i = static_cast<std::size_t>(&spec - d.robots.data());
  if (i >= parts.robots.size()) return Error::internal("make_robot: a robot that is not the deployment's");
  if (!parts.traffic && simulated_robots(d) > 1) parts.traffic = make_traffic(d, parts);
  auto sim =
      std::make_unique<sim::SimRobot>(clock, parts.map, *parts.world,
                                      sim::SimRobotOptions{.start = start,
                                                           .dock = parts.robots[i].dock,
                                                           .seed = seed,
                                                           .battery = d.robots.size() > 1 ? spec.battery : std::nullopt,
                                                           .speed = spec.speed,
                                                           .actions = spec.actions,
                                                           .name = spec.name,
                                                           .traffic = parts.traffic.get()});
  const sim::SimRobot* s = sim.get();
  return DeploymentRobot{.robot = std::move(sim), .charging_time = [s] { return s->charging_time(); }};
}

exec::ExecutorOptions robot_options(const Deployment& d, const RobotSpec& spec, const RobotNodes& nodes) {
  exec::ExecutorOptions options = d.executor;
  options.dock = nodes.dock;
  options.seed = d.seed;
  options.robot_name = spec.name;
  if (spec.capacity) options.capacity = *spec.capacity;
  return options;
}

std::unique_ptr<fleet::Allocator> make_allocator(const Deployment& d) {
  std::unique_ptr<fleet::Allocator> allocator;
  if (d.allocator == AllocatorKind::kGreedy) {
    allocator = std::make_unique<fleet::GreedyAllocator>();
  } else {
    fleet::FleetSchedulerAllocatorOptions options{.seed = d.seed};
    for (const RobotSpec& r : d.robots)
      if (!r.vda5050 && r.speed != 1.0) options.speed_factors[r.name] = r.speed;
    allocator = std::make_unique<fleet::FleetSchedulerAllocator>(std::move(options));
  }
  if (d.balance) allocator = std::make_unique<fleet::BalancedAllocator>(std::move(allocator));
  return allocator;
}

traffic::Reservations* reservations_for(const Deployment& d, DeploymentParts& parts) {
  if (d.robots.size() < 2 || !d.traffic.reservations) return nullptr;
  if (!parts.reservations) {
    parts.reservations = std::make_unique<traffic::Reservations>(
        parts.map, traffic::ReservationOptions{.lookahead = d.traffic.lookahead});
    for (const DockSpec& dock : d.docks)
      if (const auto n = parts.map.find_node(dock.node))
        parts.reservations->set_capacity(*n, node_room(d, parts.map, *n));
  }
  return parts.reservations.get();
}

traffic::Bookings* bookings_for(const Deployment& d, DeploymentParts& parts) {
  if (d.robots.size() < 2 || !d.traffic.plan_around) return nullptr;
  if (!parts.bookings) {
    parts.bookings = std::make_unique<traffic::Bookings>(parts.map);
    for (const DockSpec& dock : d.docks)
      if (const auto n = parts.map.find_node(dock.node)) parts.bookings->set_capacity(*n, node_room(d, parts.map, *n));
  }
  return parts.bookings.get();
}

}  // namespace rondo::app
