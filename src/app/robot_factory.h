// The deployment's robot: the simulated one (robot kind sim, the default) or a VDA 5050 vehicle
// driven over MQTT (kind vda5050, docs/vda5050.md), with the figures the run report reads.
//
//   Result<DeploymentRobot> r = make_robot(deployment, parts, clock);
//   fleet.add_robot(*r->robot, options);
//   r->charging_time();
#pragma once

#include <cstdint>
#include <functional>
#include <memory>

#include "deployment.h"
#include "deployment_parts.h"
#include "rondo/core/result.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/robot.h"

namespace rondo::app {

struct DeploymentRobot {
  std::unique_ptr<exec::Robot> robot;
  std::function<Duration()> charging_time;   // time on the charger (0 when the robot cannot tell)
};

// The robot starts at `start` (a VDA 5050 vehicle then says where it is); `seed` is the simulated
// robot's, which drives in `parts.world`. `parts` and `clock` must outlive it.
Result<DeploymentRobot> make_robot(const Deployment& deployment, DeploymentParts& parts, exec::Clock& clock,
                                   map::NodeIndex start, std::uint64_t seed);

// A VDA 5050 vehicle moves in real time: it needs the system clock (rondo run --realtime).
inline bool needs_realtime(const Deployment& deployment) { return deployment.vda5050.has_value(); }

}  // namespace rondo::app
