// A simulated world as a deployment describes it in one YAML file: the building's edges (a
// parametric or a replay EdgeWorld), the robot's actions and its battery.
//
//   auto zone = TimeZone::named("Europe/London");
//   Result<SimWorld> world = load_world("examples/g4s/world.yaml", map, *zone);
//   if (!world) return world.error();   // "examples/g4s/world.yaml:14: effects[0].nodes[1]: ..."
//   SimRobot robot(clock, map, *world, {.start = dock, .dock = dock});
//
// The format is docs/simulation.md: `kind: parametric` (rhythms on the given map) or
// `kind: replay` (with `logs:`, the Witham Wharf log folder, relative to the world file). Every
// error names the file, the line and the field.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/timezone.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/action_model.h"
#include "rondo/sim/battery_model.h"
#include "rondo/sim/edge_world.h"
#include "rondo/sim/traffic.h"

namespace rondo::sim {

// The robot's door sensor: after every edge attempt it looks at the doors within `range_m` of the
// node it is at, and sees each open or closed as the world has it, except that it misses a door
// with probability `miss_rate`. Off unless the world file has `door_sensor`.
struct DoorSensor {
  bool enabled = false;
  double range_m = 3.0;
  double miss_rate = 0.1;
  bool operator==(const DoorSensor&) const = default;
};

// How long people take to confirm that they have loaded or unloaded the robot, per place (the
// person who works there): the true mean of the named actions' durations at that place, whatever
// the executor expects. The action's profile (ActionModel) spreads it. Off unless the world file
// has `confirmation`.
struct Confirmation {
  std::vector<std::string> actions{"load", "unload"};
  std::optional<Duration> fallback{};    // places not listed; absent: the executor's expectation
  std::map<std::string, Duration> places{};  // node name -> mean time to confirm
  // The true mean at `place` for `action`, if the world decides it.
  std::optional<Duration> at(const std::string& action, const std::string& place) const;
  bool operator==(const Confirmation&) const = default;
};

struct SimWorld {
  std::unique_ptr<EdgeWorld> edges;
  ActionModel actions;
  BatteryModel battery;
  DoorSensor door_sensor;
  Confirmation confirmation;
  TrafficOptions traffic;  // for a building with several robots (traffic.h)
};

Result<SimWorld> load_world(const std::filesystem::path& file, const map::TopoMap& map, const TimeZone& zone);
// A `battery:` block (docs/simulation.md, "Battery"): of a world file, or of a deployment file,
// where it replaces the world's.
Result<BatteryModel> decode_battery(const Field& f);
// The same from a parsed document; `base` is the folder relative paths (replay logs) start from.
Result<SimWorld> decode_world(const Document& doc, const std::filesystem::path& base, const map::TopoMap& map,
                              const TimeZone& zone);

}  // namespace rondo::sim
