// The robots and docks of a deployment file (docs/deployment.md, "The robots"): `robot:` (a fleet
// of one, named "robot"), or `robots:` (a fleet), and `docks:`. Checked here against each other
// (names, kinds, docks' room); their nodes are checked against the map by load_parts().
//
//   RONDO_RETURN_IF_ERROR(decode_robots(root, d));   // "deployment.yaml:9: robots[1].name: ..."
#pragma once

#include "deployment.h"
#include "rondo/core/document.h"
#include "rondo/core/result.h"

namespace rondo::app {

// Reads robot, robots, docks, allocator and battery of the deployment's root mapping into d.robots,
// d.docks and d.allocator; d.dock must be read already.
Status decode_robots(const Field& root, Deployment& d);

}  // namespace rondo::app
