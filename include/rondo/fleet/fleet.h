// The fleet (DESIGN.md, "A fleet"): what belongs to the building. It keeps the task pool (the
// building's TaskBook), decides which robot does each task (its Allocator), makes the routines' tasks
// every day, refits what the building learned every night, brings everything back after a restart,
// and routes each change to the robot whose task it is. Each robot is an exec::Executor: its task
// run and steps, journeys, monitors, battery and charging. A deployment with one robot is a fleet of
// one; there is no other path.
//
//   fleet::Fleet fleet(clock, map, store, zone, options);
//   fleet.add_robot(robot, options);                  // every robot, before restore() and start()
//   fleet.add_routines(routines);
//   fleet.start();
//   fleet.add_tasks({task}, "api");                   // allocated, stored, then scheduled by its robot
//   clock.run_until(end);
//
// Everything runs on the clock's thread, robots and API alike (the service posts to it).
#pragma once

#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/routine.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/building.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/exec/robot.h"
#include "rondo/fleet/allocator.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/schedule/scheduler.h"
#include "rondo/store/requests.h"
#include "rondo/store/store.h"

namespace rondo::fleet {

class Fleet {
 public:
  // Precondition: clock, map and store outlive the fleet. `options`: what the robots share (the
  // slots, the refit, the online model); each robot's own come with add_robot(). Empty `models`:
  // learned from the map's distances (exec::Building); empty `allocator`: GreedyAllocator.
  Fleet(exec::Clock& clock, const map::TopoMap& map, store::Store& store, const TimeZone& zone,
        const exec::ExecutorOptions& options, std::shared_ptr<plan::LearnedEdgeModels> models = {},
        std::unique_ptr<Allocator> allocator = {});
  ~Fleet();
  Fleet(const Fleet&) = delete;
  Fleet& operator=(const Fleet&) = delete;

  // A robot of the fleet, by `options.robot_name` (precondition: a name not taken, a dock on the
  // map; the robot outlives the fleet). Before restore() and start().
  exec::Executor& add_robot(exec::Robot& robot, exec::ExecutorOptions options,
                            std::unique_ptr<schedule::Scheduler> scheduler = {});
  const std::vector<std::unique_ptr<exec::Executor>>& robots() const { return robots_; }
  // The robot named so, or nothing.
  exec::Executor* find_robot(std::string_view name) const;
  // The only robot of a fleet of one (the first of a larger one).
  exec::Executor& robot() const { return *robots_.front(); }

  // Accepts tasks (committed to the store before this returns, each allocated to a robot), then
  // each robot schedules what it was given. kInvalidInput for a task that cannot be run here (an
  // unknown node or robot, no window, a duplicate id, an id the store already holds, actions no
  // robot can run), kStorage when the store cannot write; either way nothing is added. With
  // `taken` (a request of the store's queue), the request is marked taken in the transaction that
  // stores the tasks, or in the one of its `rejected` event.
  Status add_tasks(std::vector<Task> tasks, std::string_view source, const store::RequestTaken* taken = nullptr);
  Status add_task(Task task, std::string_view source) { return add_tasks({std::move(task)}, source); }
  // Refuses a queued request that cannot be carried out: a `rejected` request event (code
  // `invalid request`, about "request N") and the request marked taken, in one transaction.
  void reject_request(const store::RequestTaken& taken, const std::string& reason);
  // Through the task's robot (exec::Executor::cancel_task, confirm_action, update_task), with its
  // answers: kNotFound for an unknown task, kConflict for one that is over.
  Status cancel_task(const TaskId& id, const std::string& reason);
  Status confirm_action(const TaskId& id, const std::string& by);
  Status update_task(const TaskId& id, std::optional<TimeWindow> window, std::optional<int> priority);

  // Routines become tasks every day at local midnight (and at start() for the current day).
  void add_routines(std::vector<Routine> routines);
  const std::vector<Routine>& routines() const { return routines_; }
  // Adds a routine while running: today's instances that can still be met are added at once.
  // kInvalidInput for a name already taken, a node not on the map, or actions no robot runs.
  Status add_routine_now(Routine routine);
  // Adds routines a queued request asks for (store/requests.h), all or none: kInvalidInput for a
  // name already taken (or twice in `routines`), a node not on the map or actions no robot runs, and
  // the request is marked taken with a `rejected` request event (code `invalid request`) that says
  // why. Otherwise the request is marked taken (with `taken.meta`: what keeps the routines over a
  // restart) in one transaction with a request event `routines added` whose reason is `why`, and
  // today's instances that can still be met are added (before start(), start() adds them). The
  // store's error when the request cannot be marked (kConflict: taken already); nothing is added then.
  Status add_routines_now(std::vector<Routine> routines, const store::RequestTaken& taken, const std::string& why);
  // Forgets a routine: no more instances from the next day on (today's stay). kNotFound if unknown.
  Status remove_routine(const std::string& name);

  // Rebuilds the book from the store after a restart (fleet_restore.cpp): call it after every
  // add_robot() and add_routines(), before start() and before any add_tasks(). Final tasks come back
  // final; queued ones queued on their robot (on-demand ones in its on-demand queue, drops for now
  // deferred); a task that was running comes back `queued` with an `interrupted` event (or `failed`
  // when its window no longer allows it); a task of a robot the deployment no longer has is
  // allocated again. Errors: kStorage (a store that cannot be read back; nothing is restored),
  // kInternal (called late).
  Status restore();
  // Starts every robot, adds today's routine tasks, schedules what was restored, and posts the
  // nightly refit and the midnights.
  void start();

  const std::map<TaskId, exec::TaskRecord>& tasks() const { return building_.book.records(); }
  const std::vector<TaskId>& task_order() const { return building_.book.order(); }  // in the order added
  const exec::TaskBook& book() const { return building_.book; }
  // One task, from memory or (a finished one) from the store; nothing for an unknown id.
  Result<std::optional<exec::TaskRecord>> task(const TaskId& id) const {
    return building_.book.lookup(id, building_.zone);
  }
  // Store writes that failed (the run goes on; the caller reports them).
  const std::vector<std::string>& write_errors() const { return building_.book.write_errors(); }
  const plan::LearnedEdgeModels& models() const { return *building_.models; }
  const exec::TravelCache& travel_cache() const { return building_.travel; }
  const TimeZone& zone() const { return building_.zone; }
  const exec::Building& building() const { return building_; }
  // The building's reservations (docs/traffic.md), before the first add_robot(): every robot then
  // reserves its way. Must outlive the fleet.
  void set_reservations(traffic::Reservations* reservations) { building_.reservations = reservations; }
  // The bookings of the robots' planned stops (docs/traffic.md, "Planning around each other"),
  // before the first add_robot(): every robot then plans around the others'. Must outlive the fleet.
  void set_bookings(traffic::Bookings* bookings) { building_.bookings = bookings; }
  int refits() const { return refits_; }  // nightly refits that fitted the edge models
  // The learned probability that `door` is open at `t` (nothing before the first refit with data).
  std::optional<double> door_open_probability(const std::string& door, Time t) const;
  std::vector<std::string> door_names() const;  // the doors with a learned model, by name
  // The loading and unloading times learned so far, per action and place.
  std::vector<exec::LearnedActionTime> loading_times() const;

 private:
  // Checks a task against the building and the robots: nothing, or why it cannot run here.
  Status accept(const Task& task) const;
  Status runs_here(const Task& task) const;  // its places are on the map, its robot in the fleet
  // The robots that may take `task`: its own when it names one, else those that run its actions
  // and are in service (all that run them when none is).
  std::vector<std::size_t> eligible(const Task& task) const;
  // Why no robot (or not the robot it names) can run these actions; nothing when one can.
  std::optional<std::string> cannot_run(const Task& task) const;
  std::optional<std::string> cannot_run(const std::vector<Action>& actions) const;
  // The robot of each task, a delivery job's halves together, with one a job already has. `skip`:
  // robots left out for a task (as indices); a task left with none gets robots_.size().
  using Skip = std::function<bool(const Task& task, std::size_t robot)>;
  std::vector<Allocation> allocate(const std::vector<Task>& tasks, const Skip& skip = {});
  std::size_t index_of(const std::string& robot) const;  // robots_.size() when none
  exec::Executor& robot_of(const TaskId& id) const;      // the robot that holds the task
  // Gives recorded tasks to their robots, in the order of the robots.
  void hand_out(const std::vector<TaskId>& ids);
  // Re-allocation (fleet_reallocation.cpp): a robot that cannot work (ExecutorOptions::
  // reallocate_after after a fault began or it went out of service, and still so) hands back its
  // unstarted tasks, which go to the robots that can work, each with a `re-allocated` event; in a
  // fault, its running task too, with its progress, once its run has stopped
  // (Executor::hand_back_running).
  void watch(exec::Executor& robot);
  void reallocate_from(exec::Executor& robot);
  void move_tasks(exec::Executor& robot, const std::vector<TaskId>& ids);
  // A task preempted on `robot` for an on-demand one goes back to the fleet's pool: allocated again
  // over every robot (Executor::on_preempted).
  void offer_preempted(exec::Executor& robot, const TaskId& id);
  // Drops for now, fleet-wide (fleet_drops.cpp): a task a robot drops for now goes to another robot
  // whose schedule it fits, one that has not dropped it within a slot; a robot that finds itself
  // free takes what fits it of the others' drops.
  void offer_dropped(exec::Executor& from, const std::vector<TaskId>& ids);
  void offer_to_free(exec::Executor& robot);
  // Moves those of `tasks` (all held by `from`) that the allocator fits on another robot.
  void move_if_fits(exec::Executor& from, const std::vector<Task>& tasks, const Skip& skip);

  // Daily (fleet_daily.cpp).
  void create_routine_tasks(std::chrono::year_month_day day);
  std::vector<Task> todays_instances(std::size_t first_routine) const;
  void schedule_midnight();
  void schedule_refit();
  void refit();

  exec::Building building_;
  exec::ExecutorOptions options_;
  std::unique_ptr<Allocator> allocator_;
  std::vector<std::unique_ptr<exec::Executor>> robots_;
  std::vector<Routine> routines_;
  // When each robot last dropped each task for now (fleet_drops.cpp): it is not offered the task
  // again within a slot.
  std::map<TaskId, std::map<std::string, Time>> dropped_by_;
  std::set<std::string> free_posted_;  // robots with an offer_to_free() waiting on the clock
  int refits_ = 0;
  bool started_ = false;
};

}  // namespace rondo::fleet
