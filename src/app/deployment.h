// A deployment: everything `rondo run` needs to live a robot's weeks, in one YAML file whose
// paths are relative to it (docs/deployment.md).
//
//   rondo_deployment: 1
//   name: g4s
//   map: map.yaml                  # any map format rondo reads
//   time_zone: Europe/London
//   dock: ChargingPoint
//   start: 2026-11-23              # local date of the first day
//   days: 21
//   seed: 1
//   routines: routines.yaml        # task file: routines (and one-off tasks)
//   world: world.yaml              # the simulated building (docs/simulation.md): kind sim only
//   requests: requests.yaml        # optional: people's on-demand requests
//   places: places.yaml            # optional: rooms, aliases and people for commands in words
//   executor: {navigation_overrun: 2.0, navigation_slack: 60s, action_overrun: 1.5,
//              action_slack: 30s, dock_when_waiting_over: 15m, refit_at: "02:00",
//              slot_width: 15m, scheduler_polls: 20000}
//   robot: {kind: vda5050, broker: "mqtt://127.0.0.1:1883", interface_name: uagv,   # optional;
//           manufacturer: acme, serial_number: agv-7, map_id: g4s}                  # kind: sim
//   robots:                        # or a fleet, in place of robot: (docs/fleet.md)
//     - {name: r1, kind: sim, dock: Dock1, start: Hall, actions: [load, unload], capacity: 2,
//        speed: 0.8, battery: {...}}
//   docks: [{node: Dock1, capacity: 2}]   # optional: a dock not listed has room for one robot
//   allocator: fleet               # optional: fleet (the fleet scheduler, default) or greedy
//   balance: false                 # optional: spread work and battery across the robots
//   traffic: {reservations: true, lookahead: 2, plan_around: true}   # optional: a fleet reserves its
//                                   # way and plans around its robots' stops (docs/traffic.md)
//   store: {kind: postgresql, url: "postgresql://rondo@db/fleet", password_file: pw}  # optional;
//                                   # rondo serve's store (default: rondo.sqlite in its data folder)
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/executor.h"
#include "rondo/sim/battery_model.h"
#include "rondo/store/store.h"
#include "rondo/vda5050/config.h"

namespace rondo::app {

// One robot of the deployment: `robot:` (named "robot") or an entry of `robots:`.
struct RobotSpec {
  std::string name = "robot";
  std::string where;  // "file:line: robots[i]", for errors found once the map is loaded
  // A VDA 5050 vehicle; nothing for the simulated robot (kind: sim, the default).
  std::optional<vda5050::Vda5050Config> vda5050;
  std::string dock;   // empty: the deployment's dock
  std::string start;  // empty: its dock
  // The actions it runs (the simulated robot's; a vehicle's factsheet says its own); nothing: any.
  std::optional<std::vector<std::string>> actions;
  std::optional<int> capacity;  // items on board at once; nothing: executor.capacity
  // The simulated robot's battery (`battery:` of its entry, or the deployment's for `robot:`), in
  // place of the world file's; and its speed, a factor on every edge's time in the world.
  std::optional<sim::BatteryModel> battery;
  double speed = 1.0;
};

// Which allocator decides the robot of each task (`allocator:`, docs/fleet.md, "Allocation").
enum class AllocatorKind {
  kFleet,   // fleet::FleetSchedulerAllocator: the fleet scheduler over every robot's plan
  kGreedy,  // fleet::GreedyAllocator: cheapest insertion into each robot's schedule
};

// `reference:`: the figures of the real deployment a simulated one stands for, set beside the
// run's own in report.json ("reference"), so a reader sees how near the load is.
struct ReferenceFigures {
  std::string name;  // where the figures come from
  int days = 0;
  std::optional<std::int64_t> tasks;
  std::optional<double> distance_km;
};

// A place where robots dock and charge, and how many robots it has room for at once.
struct DockSpec {
  std::string node;
  int capacity = 1;
  std::string where;
};

struct Deployment {
  std::filesystem::path file;  // where it was read from
  std::string name;
  std::filesystem::path map;
  TimeZone zone = TimeZone::utc();
  std::string dock;
  std::string dock_where;  // "file:line: dock", for errors found once the map is loaded
  std::chrono::year_month_day start{};
  int days = 21;
  std::uint64_t seed = 1;
  std::optional<std::filesystem::path> routines;
  // The simulated building: always for the simulated robot, never for a VDA 5050 vehicle.
  std::optional<std::filesystem::path> world;
  std::optional<std::filesystem::path> requests;
  std::optional<std::filesystem::path> places;  // commands in words through `rondo serve`'s API
  // dock is filled in once the map is loaded; risk_alpha is exec::kDeploymentRiskAlpha unless the
  // file says otherwise (null: expected values).
  exec::ExecutorOptions executor{.risk_alpha = exec::kDeploymentRiskAlpha};
  // The robots, at least one; `robot:` (or neither) is a fleet of one named "robot".
  std::vector<RobotSpec> robots;
  // Docks with room for more than one robot (or listed for clarity); `dock` and every robot's dock
  // not listed here has room for one.
  std::vector<DockSpec> docks;
  AllocatorKind allocator = AllocatorKind::kFleet;
  bool balance = false;  // `balance:` (fleet::BalancedAllocator around the allocator)
  // `traffic:` (docs/traffic.md): a fleet's robots reserve their way ahead (on by default with two
  // robots or more), `lookahead` edges at a time, and plan around each other's stops (the same).
  struct Traffic {
    bool reservations = true;
    std::size_t lookahead = 2;
    bool plan_around = true;
  } traffic{};
  // `store:`: where `rondo serve` keeps its store; none: rondo.sqlite in its data folder
  // (docs/deployment.md, "The store").
  std::optional<store::StoreLocation> store;
  std::optional<ReferenceFigures> reference;

  bool has_vehicle() const;    // a VDA 5050 vehicle among the robots
  bool has_simulated() const;  // a simulated robot among them
  const RobotSpec* find_robot(std::string_view name) const;
  int dock_capacity(std::string_view node) const;  // 1 unless `docks:` says otherwise
};

// Reads and checks a deployment file; paths come back resolved against its folder. Errors name
// file:line and the field.
Result<Deployment> load_deployment(const std::filesystem::path& file);

// The bundled example, examples/g4s/deployment.yaml: installed beside the binary
// (PREFIX/share/rondo/examples), else in the source tree the binary was built from.
std::filesystem::path default_deployment();

}  // namespace rondo::app
