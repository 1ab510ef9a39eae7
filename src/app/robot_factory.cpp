#include "robot_factory.h"

#include <fmt/format.h>

#include "rondo/sim/sim_robot.h"
#include "rondo/vda5050/vda5050_robot.h"

namespace rondo::app {

Result<DeploymentRobot> make_robot(const Deployment& d, DeploymentParts& parts, exec::Clock& clock,
                                   map::NodeIndex start, std::uint64_t seed) {
  if (d.vda5050) {
    RONDO_ASSIGN_OR_RETURN(std::unique_ptr<vda5050::Vda5050Robot> vehicle,
                           vda5050::Vda5050Robot::create(clock, parts.map, *d.vda5050, {.start = start}));
    return DeploymentRobot{.robot = std::move(vehicle), .charging_time = [] { return Duration{0}; }};
  }
  // load_deployment gives the simulated robot a world, always.
  if (!parts.world) return Error::internal(fmt::format("{}: the simulated robot has no world", d.file.string()));
  parts.world->edges->set_seed(d.seed);  // the building's own spells: the deployment's seed, also on resume
  auto sim = std::make_unique<sim::SimRobot>(clock, parts.map, *parts.world,
                                             sim::SimRobotOptions{.start = start, .dock = parts.dock, .seed = seed});
  const sim::SimRobot* s = sim.get();
  return DeploymentRobot{.robot = std::move(sim), .charging_time = [s] { return s->charging_time(); }};
}

}  // namespace rondo::app
