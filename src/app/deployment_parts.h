// Everything a deployment names, loaded and checked against each other before anything runs or is
// written (the map, the dock, the routines and tasks, the simulated world, the requests, the
// places): every node they name is on the map, and every error names the file, the line and the
// node. A VDA 5050 vehicle's deployment has no simulated world.
//
//   Result<DeploymentParts> parts = load_parts(deployment);   // reads files, writes nothing
//   if (!parts) return parts.error();   // "routines.yaml:12: routines[0].task.start_node: node ..."
#pragma once

#include <optional>

#include "deployment.h"
#include "rondo/core/result.h"
#include "rondo/core/task_codec.h"
#include "rondo/lang/places.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/request_generator.h"
#include "rondo/sim/sim_world.h"

namespace rondo::app {

struct DeploymentParts {
  map::TopoMap map;
  map::NodeIndex dock = 0;
  TaskFile plan;  // routines and one-off tasks
  std::optional<sim::SimWorld> world;  // the simulated robot's building; none for a VDA 5050 vehicle
  std::optional<sim::RequestGenerator> people;
  std::optional<lang::Places> places;  // the deployment's places file, checked against the map
};

Result<DeploymentParts> load_parts(const Deployment& deployment);

}  // namespace rondo::app
