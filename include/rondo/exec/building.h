// What every robot of a deployment shares (DESIGN.md, "A fleet"): the task book, the edge models
// that all robots' traversals feed and the travel caches that read them, the loading times, the
// door models, what journeys found of the edges, and the weekly memory. One thread uses it: the
// clock's. The fleet owns it; each robot's Executor borrows it.
//
//   exec::Building building(clock, map, store, zone, options);
//   exec::Executor ex(building, robot, options);
#pragma once

#include <memory>

#include "rondo/core/result.h"

#include "rondo/core/timezone.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor_types.h"
#include "rondo/exec/map_travel.h"
#include "rondo/exec/task_book.h"
#include "rondo/learn/robot_speeds.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/store/store.h"

namespace rondo::learn {
class EdgeModels;
class WeeklyMemory;
}  // namespace rondo::learn
namespace rondo::traffic {
class Reservations;
class Bookings;
}

namespace rondo::exec {

class DoorModels;
class FoundBlocked;
class LoadingTimes;
class SpecTasks;

class Building {
 public:
  // Precondition: clock, map and store outlive the building. Empty `models`: edge models from the
  // map's distances, read online or offline as `options.online_model` says (refitted nightly).
  Building(Clock& clock, const map::TopoMap& map, store::Store& store, const TimeZone& zone,
           const ExecutorOptions& options, std::shared_ptr<plan::LearnedEdgeModels> models = {});
  ~Building();
  Building(const Building&) = delete;
  Building& operator=(const Building&) = delete;

  // What was learned before a restart, read back from the store: the loading times (of the tasks
  // in the book: restore them first) and the door models. Errors: kStorage.
  Status restore_learning();
  // The nightly refit (building_learning.cpp): the door models, then the robots' speeds and the
  // edge models from the traversal log of the last `refit_window` in standard time, with the week
  // (building_weekly.cpp) and the attempt laws. False when there was nothing to fit, or the store could not be read (a
  // write error).
  bool refit();

  Clock& clock;
  const ExecutorOptions options;  // what the robots share: slots, the refit, the online model
  const map::TopoMap& map;
  store::Store& store;
  const TimeZone zone;
  // What the robots plan with: the live model when online.
  std::shared_ptr<plan::LearnedEdgeModels> models;
  plan::TravelPlanner planner;
  TravelCache travel;
  // The snapshot read offline, only for NavigationRecord::offline_expected (with the online model
  // off, `travel` reads the snapshot itself and this cache is not used).
  std::shared_ptr<plan::LearnedEdgeModels> offline_models;
  plan::TravelPlanner offline_planner;
  TravelCache offline_travel;
  TaskBook book;
  // Each robot's pace against the fleet's standard robot, fitted at every refit from the window's
  // log (learn/robot_speeds.h): the edge models learn standard times, and each robot reads them as
  // its own through its factor. A lone robot's is 1.
  learn::RobotSpeeds speeds;
  std::unique_ptr<LoadingTimes> loading;               // loading and unloading times, per action and place
  std::unique_ptr<FoundBlocked> found_blocked;         // failures in a row, edges held blocked
  std::unique_ptr<DoorModels> door_models;             // when doors are open, learned
  std::unique_ptr<learn::WeeklyMemory> weekly_memory;  // null until the first refit
  std::unique_ptr<SpecTasks> spec_tasks;               // spec tasks' automata and product plans
  // The traffic manager's reservations (docs/traffic.md), when the robots reserve their way (a
  // fleet's deployment: `traffic: reservations`); owned by the fleet. Null: robots move freely.
  traffic::Reservations* reservations = nullptr;
  std::vector<TrafficWait> traffic_waits;  // every journey's wait for another robot, in order
  // The robots' planned stops (docs/traffic.md, "Planning around each other"), when they plan
  // around each other (`traffic: {plan_around: true}`); owned by the fleet. Null: each plans alone.
  traffic::Bookings* bookings = nullptr;
  TrafficDeferrals deferrals;  // departures put off for another robot's stop

 private:
  void refit_doors();
  Status restore_door_models();
  Status restore_loading_times();
  // The live weekly term: adds the whole local days since the last refit to the weekly memory
  // (loaded from the store the first time), saves it, and returns `fitted` with the term the memory
  // chooses for each edge.
  std::shared_ptr<const learn::EdgeModels> with_week(std::shared_ptr<const learn::EdgeModels> fitted);
};

}  // namespace rondo::exec
