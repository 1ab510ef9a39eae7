// A robot of the deployment: the simulated one (robot kind sim, the default) or a VDA 5050 vehicle
// driven over MQTT (kind vda5050, docs/vda5050.md), with the figures the run report reads.
//
//   Result<DeploymentRobot> r = make_robot(deployment, deployment.robots[i], parts, clock, start, seed);
//   fleet.add_robot(*r->robot, options);
//   r->charging_time();
//   fleet::Fleet fleet(clock, map, store, zone, options, {}, make_allocator(deployment));
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "deployment.h"
#include "deployment_parts.h"
#include "rondo/core/result.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/robot.h"
#include "rondo/fleet/allocator.h"

namespace rondo::app {

struct DeploymentRobot {
  std::unique_ptr<exec::Robot> robot;
  std::function<Duration()> charging_time;   // time on the charger (0 when the robot cannot tell)
};

// `spec` is one of `deployment.robots`. It starts at `start` (a VDA 5050 vehicle then says where it
// is); `seed` is the simulated robot's, which drives in `parts.world` with the fleet's other
// simulated robots. With two simulated robots or more, they share `parts.traffic` (made with the
// first: the map's capacities, a listed dock's room where larger). `parts` and `clock` must
// outlive it.
Result<DeploymentRobot> make_robot(const Deployment& deployment, const RobotSpec& spec, DeploymentParts& parts,
                                   exec::Clock& clock, map::NodeIndex start, std::uint64_t seed);

// The executor's options for `spec`: the deployment's, with the robot's name, dock and capacity.
exec::ExecutorOptions robot_options(const Deployment& deployment, const RobotSpec& spec, const RobotNodes& nodes);

// The deployment's allocator (`allocator:`): the fleet scheduler with each simulated robot's speed
// as its speed factor (a vehicle's is 1: it reports none) and the deployment's seed, or the greedy.
std::unique_ptr<fleet::Allocator> make_allocator(const Deployment& deployment);

// The building's reservations (made once, kept in `parts`) when the deployment's robots reserve
// their way: two robots or more and `traffic: {reservations: true}` (the default); else null.
traffic::Reservations* reservations_for(const Deployment& deployment, DeploymentParts& parts);
// The bookings of the robots' planned stops (made once, kept in `parts`) when they plan around
// each other: two robots or more and `traffic: {plan_around: true}` (the default); else null.
traffic::Bookings* bookings_for(const Deployment& deployment, DeploymentParts& parts);

// A VDA 5050 vehicle moves in real time: it needs the system clock (rondo run --realtime).
inline bool needs_realtime(const Deployment& deployment) {
  return deployment.has_vehicle();
}

}  // namespace rondo::app
