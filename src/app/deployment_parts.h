// Everything a deployment names, loaded and checked against each other before anything runs or is
// written (the map, the dock, the routines and tasks, the simulated world, the requests, the
// places): every node they name is on the map, and every error names the file, the line and the
// node. A VDA 5050 vehicle's deployment has no simulated world. Every robot docks and starts on the
// map, and every task and routine names a robot of the deployment (or none) and actions that some
// robot runs (a robot that does not list its actions runs any). Simulated robots of a fleet do not
// start more of them on one node than it holds (node_room).
//
//   Result<DeploymentParts> parts = load_parts(deployment);   // reads files, writes nothing
//   if (!parts) return parts.error();   // "routines.yaml:12: routines[0].task.start_node: node ..."
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "deployment.h"
#include "rondo/core/result.h"
#include "rondo/core/task_codec.h"
#include "rondo/lang/places.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/request_generator.h"
#include "rondo/sim/sim_world.h"
#include "rondo/sim/traffic.h"
#include "rondo/traffic/bookings.h"
#include "rondo/traffic/reservations.h"

namespace rondo::app {

// Where one robot of the deployment docks and starts, on the map.
struct RobotNodes {
  map::NodeIndex dock = 0;
  map::NodeIndex start = 0;
};

struct DeploymentParts {
  map::TopoMap map;
  map::NodeIndex dock = 0;         // the deployment's dock
  std::vector<RobotNodes> robots;  // per Deployment::robots, in its order
  TaskFile plan;  // routines and one-off tasks
  std::optional<sim::SimWorld> world;  // the simulated robot's building; none for a VDA 5050 vehicle
  std::optional<sim::RequestGenerator> people;
  std::optional<lang::Places> places;  // the deployment's places file, checked against the map
  // The building's traffic, shared by its simulated robots when there are several (made with the
  // first of them, by make_robot: it refers to `map` where the parts finally live).
  std::unique_ptr<sim::Traffic> traffic{};
  // The traffic manager's reservations (docs/traffic.md), for a fleet whose robots reserve their
  // way (reservations_for()).
  std::unique_ptr<traffic::Reservations> reservations{};
  // The robots' planned stops (docs/traffic.md, "Planning around each other"), for a fleet whose
  // robots plan around each other (bookings_for()).
  std::unique_ptr<traffic::Bookings> bookings{};
};

// The robots a node holds at once: its capacity on the map, or a listed dock's room when larger.
int node_room(const Deployment& deployment, const map::TopoMap& map, map::NodeIndex node);

Result<DeploymentParts> load_parts(const Deployment& deployment);

}  // namespace rondo::app
