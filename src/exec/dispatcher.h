// The dispatcher: what the robot does next when it is free. It owns the executor's queues (the
// planned order of standard tasks, on-demand tasks waiting their turn, tasks dropped for now, the
// schedule's charges), changed only through methods that say what happens to a task, and reads the
// book and the travel estimates; the executor carries out its decisions.
//
//   Decision d = dispatcher.next(robot.location(), clock.now());
//   switch (d.kind) { case Decision::Kind::kRun: ... }
#pragma once

#include <algorithm>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/timezone.h"
#include "rondo/exec/executor_types.h"
#include "rondo/exec/map_travel.h"
#include "rondo/exec/outcome.h"
#include "rondo/exec/task_book.h"
#include "rondo/map/topo_map.h"
#include "rondo/traffic/bookings.h"

namespace rondo::exec {

struct Decision {
  enum class Kind {
    kRun,        // start `task` now
    kWait,       // `task` is next but early: wait where the robot is until `until`, then go (`reason`:
                 // whose stop it waits to pass, when another robot's; `traffic_delay`: how much later)
    kFail,       // `task` can no longer start in time (`outcome`, `reason`); decide again after it
    kDock,       // go to the dock (idle, or a long wait ahead)
    kIdleUntil,  // on the dock with a long wait ahead: look again at `until`
    kStay,       // nothing to do, on the dock
    kCharge,     // a planned charge: on the charger until `level` or `until`, whichever comes first
  };
  Kind kind = Kind::kStay;
  TaskId task{};
  Time until{};
  Outcome outcome = Outcome::kNone;
  std::string reason{};
  double level = 1;        // kCharge: the level to reach
  Duration length{0};      // kCharge: planned on the charger
  Duration traffic_delay{0};  // kWait: how much later it sets out for another robot's stop
};

// A charge the schedule planned (charge_planning.h): at the dock from `start` to `end`, before
// the task `before` (nothing: after the last task), to reach about `target`.
struct PlannedCharge {
  Time start{};
  Time end{};
  double target = 1;
  std::optional<TaskId> before{};
};

class SpecTasks;

class Dispatcher {
 public:
  // Everything given outlives the dispatcher.
  Dispatcher(const map::TopoMap& map, const TravelCache& travel, const TaskBook& book, const ExecutorOptions& options,
             const TimeZone& zone, const SpecTasks* specs = nullptr)
      : map_(map), travel_(travel), book_(book), options_(options), zone_(zone), specs_(specs) {}

  // The queues, read.
  const std::vector<TaskId>& planned() const { return planned_; }    // standard, in the schedule's order
  const std::deque<TaskId>& on_demand() const { return on_demand_; }  // on-demand, waiting for the robot
  const std::vector<TaskId>& deferred() const { return deferred_; }   // dropped for now
  const std::vector<PlannedCharge>& charges() const { return charges_; }  // the schedule's, in its order
  bool is_planned(const TaskId& id) const;
  bool is_deferred(const TaskId& id) const;

  // The queues, changed.
  // A new schedule: its standard tasks in order, and its charges.
  void follow_schedule(std::vector<TaskId> order);
  void follow_charges(std::vector<PlannedCharge> charges) { charges_ = std::move(charges); }
  // A new on-demand task waits behind the others.
  void queue_on_demand(const TaskId& id) { on_demand_.push_back(id); }
  // A task goes back to the head of the planned order, or of the on-demand queue (once).
  void put_first_in_plan(const TaskId& id);
  void put_first_on_demand(const TaskId& id);
  // A task the schedule dropped for now, and one offered again that fits.
  void defer(const TaskId& id);
  void undefer(const TaskId& id) { std::erase(deferred_, id); }
  // Of the deferred tasks, only `still` stay (the others ended).
  void keep_deferred(std::vector<TaskId> still) { deferred_ = std::move(still); }
  // Takes a task out of the planned order (it is offered to the scheduler again).
  void unplan(const TaskId& id) { std::erase(planned_, id); }

  // The next thing to do from `here` at `now`. A decision about a task takes it off its queue.
  Decision next(map::NodeIndex here, Time now);
  // The next planned charge, when it comes before the next planned task.
  std::optional<PlannedCharge> charge_due(Time now);
  // The first on-demand task not held back for a blocked way at `now` (TaskRecord::not_before).
  std::optional<TaskId> ready_on_demand(Time now) const;
  // Takes a task off every queue.
  void forget(const TaskId& id);
  // Planning around the other robots' stops (docs/traffic.md): a task's departure moves so that
  // the robot arrives when it may stop there, if it still starts in time. Null: it does not.
  void plan_around(const traffic::Bookings* bookings, traffic::BookingRobot me) {
    bookings_ = bookings;
    me_ = me;
  }
  // When to set out from `here` for a standard task at `now` (its wait is over), if later, for the
  // stops at its place that the robot gives way to; nothing when it may go.
  std::optional<PutOff> put_off_now(const TaskId& id, map::NodeIndex here, Time now) const;

 private:
  const map::TopoMap& map_;
  const TravelCache& travel_;
  const TaskBook& book_;
  const ExecutorOptions& options_;
  const TimeZone& zone_;
  // Setting out at `depart` (or now, if later) with `travel` ahead: a later departure for the stops
  // at the task's place, while the task can still start in time.
  std::optional<PutOff> put_off(const TaskRecord& r, Time now, Time depart, Duration travel) const;

  const SpecTasks* specs_;
  const traffic::Bookings* bookings_ = nullptr;
  traffic::BookingRobot me_ = 0;
  std::vector<TaskId> planned_;
  std::deque<TaskId> on_demand_;
  std::vector<TaskId> deferred_;
  std::vector<PlannedCharge> charges_;
};

}  // namespace rondo::exec
