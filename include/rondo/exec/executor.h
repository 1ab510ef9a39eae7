// One robot's executor (MISSION.md §3): schedules the tasks the fleet gave it, runs them through
// its robot, watches them and reacts. Event-driven on an injected Clock: it never sleeps and never
// reads the wall clock, so the same code runs a simulated robot for weeks in seconds and a real one
// in real time. What belongs to the building (the task book, the learned models, the routines, the
// allocation of tasks to robots) is fleet::Fleet's and exec::Building's; a deployment of one robot
// is a fleet of one.
//
//   fleet::Fleet fleet(clock, map, store, zone, options);
//   exec::Executor& ex = fleet.add_robot(robot, {.dock = *map.find_node("ChargingPoint")});
//   fleet.start();                             // every robot's start(), and the day's first events
//   fleet.add_task(task, "api");               // allocated; then its robot's take(): standard ones
//   clock.run_until(end);                      //   trySchedule, on-demand ones run at once
//
// Its parts (docs/executor.md): the task book (records, state changes, the event log), the
// dispatcher (what runs next, and the queues), the task run (one task as its steps: wait, navigate,
// act, navigate to its end place; src/exec/steps.h) and the scheduler call (scheduling.h). The
// executor wires them to the robot's callbacks, the clock and the store.
//
// What it does (every task transition goes to the store's event log with an outcome code and a
// reason, through the TaskBook; every succeeded or failed edge attempt to the traversal log):
// - standard tasks: trySchedule old + new; when they do not all fit, drop the lowest-priority new
//   ones for now (schedule::try_schedule; re-offered at every reschedule while their windows can be
//   met), or preempt an interruptible running task that the dropped ones outrank: it keeps its id
//   and goes back to the queue.
// - on-demand tasks: preempt the running task if it is interruptible now (else run right after it),
//   run at once, and reschedule the rest around it.
// - cancel_task: at once when queued; through the robot when running and interruptible; at the
//   next interruptible moment otherwise.
// - robot faults: dispatch pauses and the monitors stand still until the robot is ready.
// - before leaving for a task: too early -> wait (at the dock when the wait is long); too late to
//   finish by the deadline -> the task fails and the rest is rescheduled.
// - navigation follows the MDP policy edge by edge, re-planning after every edge (so after a failed
//   one); the navigation monitor preempts past `navigation_overrun` x the expected travel time, the
//   action monitor past `action_overrun` x the processing time; a task that is not interruptible
//   (its flag, or the robot saying so at run time) is never preempted: the monitor waits.
// - idle: back to the dock, by the same NavigateStep as a task's journey (monitor, failed-edge limit,
//   blocked-edge policy), with robot events `departed`, `arrived`, `waits`, `gave up`.
// - learning: every edge attempt updates the online model of its edge (`online_model`), shared by
//   every robot of the building, so travel estimates and schedules adapt at once; the fleet refits
//   the models nightly (at `refit_at`, local time) from the traversal log of the last `refit_window`.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/routine.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/assumption.h"
#include "rondo/exec/building.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor_types.h"
#include "rondo/exec/map_travel.h"
#include "rondo/exec/outcome.h"
#include "rondo/exec/robot.h"
#include "rondo/exec/step.h"
#include "rondo/exec/task_book.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/schedule/scheduler.h"
#include "rondo/schedule/try_schedule.h"
#include "rondo/store/requests.h"
#include "rondo/store/store.h"
#include "rondo/traffic/bookings.h"

namespace rondo::exec {

struct ScheduleAnswer;
struct ScheduleCall;
struct PlannedAnswer;
class AssumptionMap;
class Charging;
class Deliveries;
class DoorModels;
class FoundBlocked;
class LoadingTimes;
class Dispatcher;
class NavigateStep;
class Opportunities;
class TaskRun;
class TrafficLink;
}  // namespace rondo::exec
namespace rondo::traffic {
struct MakeWay;
}
namespace rondo::exec {

// What the executor plans with, when the caller wants to choose (as rmf_task::TaskPlanner takes
// its configuration). Empty parts get the defaults: edge models from the map's distances (refitted
// nightly from the robot's own log, read online or offline as `online_model` says) and
// schedule::DefaultScheduler.
struct ExecutorParts {
  std::shared_ptr<plan::LearnedEdgeModels> models{};
  std::unique_ptr<schedule::Scheduler> scheduler{};
};

// Where the executor is, for people and the service API.
enum class ExecutorPhase { kIdle, kWaiting, kNavigating, kActing, kDocking };
const char* to_string(ExecutorPhase phase);

class Executor final : public RobotListener {
 public:
  // A robot of `building`. Precondition: `options.dock` is a node of the building's map; building
  // and robot outlive the executor. Empty `scheduler`: schedule::DefaultScheduler.
  Executor(Building& building, Robot& robot, ExecutorOptions options,
           std::unique_ptr<schedule::Scheduler> scheduler = {});
  ~Executor() override;
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  // --- What the fleet asks of its robot (fleet::Fleet) ---
  const std::string& name() const { return options_.robot_name; }
  const Robot& robot() const { return robot_; }
  // Why the robot cannot run one of these actions (it says so: Robot::supported_actions), or nothing.
  std::optional<std::string> cannot_run(const std::vector<Action>& actions) const;
  // Tasks the fleet recorded in the book and allocated to this robot: on-demand ones queue (and
  // preempt the running task when they may), standard ones are scheduled with the rest of its work
  // (trySchedule; from start() on).
  void take(std::vector<TaskId> ids);
  // Hands back the tasks the robot has not started, for the fleet to give to other robots (a fault
  // that lasts, a pause): those planned, on-demand and dropped for now, less those that must stay
  // (a task naming this robot, and every task of a delivery job that has begun here: its item is
  // on board, or its pickup runs). They leave every queue of this robot.
  std::vector<TaskId> release();
  // The same for the given tasks only: those of them the robot holds, has not started, and may hand
  // back.
  std::vector<TaskId> release(const std::vector<TaskId>& ids);
  // Stops the running task for the fleet to give to another robot (a fault that lasts): one it may
  // hand back as release() says, and not a spec task. It keeps its progress (the actions done, its
  // remaining time) and goes back to the queue (outcome kRobotFault), and `handed` is called with
  // its id from the clock once the run has ended, when it could be queued (its window still allows
  // it). False when nothing runs, it only waits, or it must stay.
  bool hand_back_running(std::function<void(const TaskId&)> handed);
  // The fleet's call when the robot stops being able to work: a fault begins, or it is put out of
  // service. It may release() the robot's tasks.
  void on_unable(std::function<void()> call) { unable_ = std::move(call); }
  // The fleet's call when a schedule drops tasks for now that were not dropped before (the ids), and
  // when the robot finds nothing to start now (it docks, or idles until a later task). The fleet
  // offers them to other robots (fleet_drops.cpp); it must not call back into this robot at once.
  void on_dropped(std::function<void(const std::vector<TaskId>&)> call) { dropped_ = std::move(call); }
  void on_free(std::function<void()> call) { free_ = std::move(call); }
  // The fleet's call when the running task was preempted for an on-demand one and is queued again:
  // the fleet offers it to every robot (its pool), from the clock. Without it (a fleet of one), the
  // robot schedules it again with its own work.
  void on_preempted(std::function<void(const TaskId&)> call) { preempted_ = std::move(call); }
  // The tasks dropped for now that the robot offers again to its scheduler.
  const std::vector<TaskId>& deferred() const;
  bool able() const { return !in_fault_ && !out_of_service_; }
  // What the fleet's allocator plans this robot with: its dock and its capacity (0 = unlimited).
  map::NodeIndex dock() const { return options_.dock; }
  int capacity() const { return options_.capacity; }
  Duration reallocate_after() const { return options_.reallocate_after; }
  // Where and when the robot is next free: after its running task and its on-demand queue.
  std::pair<map::NodeIndex, Time> free_at() const;
  // After a restart (fleet_restore.cpp): a task of this robot read back (what is on board follows
  // from them), the battery's learned costs, and an unfinished task back in its queues (an on-demand
  // one in the on-demand queue, one blocked by a door waiting for it, a drop for now deferred; a
  // queued standard one waits for schedule_restored()). The robot is wherever it reports (the
  // caller starts a simulated one at the stored robot_state).
  void restored(const TaskRecord& record);
  void restore_battery();
  void restore_task(const TaskId& id);
  // Starting (Fleet::start()): the robot is activated and its battery read; then, once the fleet
  // has added today's routine tasks, the queued standard tasks restored or added before are
  // scheduled; kick_soon() posts the first look at the queues. reconsider(): a look now.
  void start();
  void schedule_restored();
  void kick_soon();
  void reconsider() { kick(); }
  // Cancels a task: a queued (or waiting, or dropped-for-now) one ends `cancelled` at once; a
  // running one is stopped through the robot's cancel() when it is interruptible now, else at its
  // next interruptible moment (a `cancel pending` event says so). kNotFound for an unknown task,
  // kConflict for one already in a final state.
  Status cancel_task(const TaskId& id, const std::string& reason);
  // A person confirms the load or unload that task `id` is doing now (`by`: who or how, for the
  // log): the robot's action is ended (Robot::cancel()) and counts as done, before the simulated
  // or real person's own confirmation. A "confirmed" event. kNotFound for an unknown task,
  // kConflict when it is not loading or unloading now (executor_confirm.cpp).
  Status confirm_action(const TaskId& id, const std::string& by);

  const std::map<TaskId, TaskRecord>& tasks() const { return book_.records(); }
  const std::vector<TaskId>& task_order() const { return book_.order(); }  // in the order added
  const TaskBook& book() const { return book_; }
  // One task, from memory or (a finished one) from the store; nothing for an unknown id.
  Result<std::optional<TaskRecord>> task(const TaskId& id) const { return book_.lookup(id, zone_); }
  const ExecutorStats& stats() const { return stats_; }
  const std::vector<NavigationRecord>& navigations() const { return navigations_; }
  // Store writes that failed (the run goes on; the caller reports them).
  const std::vector<std::string>& write_errors() const { return book_.write_errors(); }
  const plan::LearnedEdgeModels& models() const { return models_; }
  const TravelCache& travel_cache() const { return travel_; }
  ExecutorPhase phase() const;
  // The running navigation's route from where the robot is (a task's or the executor's own trip
  // to the dock): the edges its policy expects to take now, in order; empty when it is not moving.
  std::vector<map::EdgeIndex> route();
  // The loading and unloading times learned so far, per action and place.
  std::vector<LearnedActionTime> loading_times() const;
  // The objects on board now (delivery jobs picked up and not yet dropped).
  std::vector<OnBoard> on_board() const;
  std::optional<TaskId> current_task() const;
  // The running standard task that an on-demand task given now would interrupt (it is interruptible
  // now); nothing when the robot runs no task, waits for one, or cannot be interrupted.
  std::optional<TaskId> preemptible_run() const;
  // What the current schedule assumes (doors open, edges passable; docs/executor.md), and what
  // broken assumptions and opportunities did so far.
  const std::vector<Assumption>& assumptions() const { return assumptions_; }
  const AssumptionStats& assumption_stats() const { return assumption_stats_; }
  // The learned probability that `door` is open at `t` (nothing before the first refit with data).
  std::optional<double> door_open_probability(const std::string& door, Time t) const;
  std::vector<std::string> door_names() const;  // the doors with a learned model, by name
  const TimeZone& zone() const { return zone_; }
  bool paused() const { return in_fault_; }
  // The battery as read so far, and what was learned of its costs (executor_battery.cpp).
  BatteryFigures battery_figures() const;
  // Below the hard threshold and not yet charged back to the resume level: nothing new starts.
  bool charging_for_battery() const;

  // An observation from outside the robot (a building sensor; POST /api/v1/observations): stored
  // without a robot and acted on exactly as the robot's own (on_observation). An empty `source`
  // becomes "building". Called on the clock's thread.
  void observe(Observation observation);

  // RobotListener
  void on_edge_finished(const EdgeAttempt& attempt) override;
  void on_action_finished(const ActionResult& result) override;
  void on_interruptible_changed(bool interruptible) override;
  void on_observation(const Observation& observation) override;
  void on_fault(const RobotFault& fault) override;
  void on_ready() override;

  // --- The service's view and changes (`rondo serve`, src/exec/executor_service.cpp) ---
  // What the executor is doing now, for the HTTP API's robot and schedule views.
  struct Activity {
    std::string phase;               // "idle", "waiting", "navigating", "acting", "docking"
    std::optional<TaskId> current;   // the task waited for, navigated to or acted on
    std::optional<RobotFault> fault; // dispatch stands still while set
    std::vector<TaskId> planned;     // the standard tasks to run, in planned order
    std::vector<TaskId> on_demand;   // on-demand tasks waiting for the running one
  };
  Activity activity() const;
  // Changes a waiting task's window and/or priority (stored, with a `changed` event) and
  // reschedules; the task keeps its id and its history. kNotFound for an unknown task, kConflict
  // for a final or running one, kInvalidInput for a change that cannot be meant (a deadline before
  // the release, a duration longer than the window, a window for an on-demand task).
  Status update_task(const TaskId& id, std::optional<TimeWindow> window, std::optional<int> priority);
  // Out of service (true) or back (false), with a robot event `out of service` / `back in service`.
  // Out of service: nothing new starts and the robot goes to the dock when free; the running task
  // finishes, or with `halt` is stopped now and goes back to the queue keeping its progress (code
  // `interrupted`; one that cannot be interrupted now finishes, with a `not halted` event); a task
  // waited for goes back at once. Back in service reschedules. Doing what is already so does nothing. Not stored: the
  // caller keeps the state (rondo serve: the store's meta).
  void set_out_of_service(bool out, bool halt, const std::string& reason);
  bool out_of_service() const { return out_of_service_; }

 private:
  // bookkeeping (executor.cpp)
  bool interruptible_now() const;
  bool running_standard() const;  // a standard task navigates or acts
  void preempt_for_on_demand(const TaskId& id);
  // An on-demand task is ready (none held back for a blocked way) and the running standard task
  // can give way to it now: it is preempted. Not interruptible now: noted, it runs right after.
  bool give_way_to_on_demand();

  // the robot (executor_robot.cpp)
  void log_battery();
  // The robot's last known state in the store (its node, pose, battery, fault), for a restart.
  void save_robot_state();
  void learn_from(const EdgeAttempt& attempt);
  void learn_from(const ActionResult& result);
  // The pending tasks' processing times from the loading times learned so far.
  void refresh_learned_durations(const std::vector<TaskId>& ids);
  // the battery (executor_battery.cpp; what is kept about it: Charging)
  void read_battery();  // a reading for the BatteryWatch
  bool charging_as_planned();  // in must_charge(): false (and rescheduled) once it is done
  // Tasks dropped for the battery are offered again while the robot stands on the charger.
  bool reoffer_for_battery();
  // In next(): when `id` is short of battery, it goes back first in its queue and a charge to
  // what it needs starts (true; then charge()).
  bool charge_first(const TaskId& id);
  // After a robot callback: below the threshold, the robot goes to charge.
  void check_battery();
  // The running task gives way to the charge now if it is interruptible (else it finishes first).
  void charge_now();
  // In next(): true while the robot must charge (it enters or leaves that state here).
  bool must_charge();
  void charge();  // to the dock, and wait there
  // What the battery estimator has learned, kept in the store's meta (kBatteryMetaKey) at the end
  // of a task and of a charge, and taken back at restore(); a stored value that cannot be read is
  // a warning (the book's write_error) and a fresh estimator.
  void save_battery();

  // running (executor_running.cpp)
  void kick();  // reconsider what to do now
  void sweep_finished();
  ActionResult confirmed_result(const ActionResult& reported);  // executor_confirm.cpp
  void next();
  void start_run(const TaskId& id, std::optional<Time> wait_until, std::string behind = {});
  void run_ended(TaskEnd end);
  void end_wait();  // the waiting task goes back to the executor, undecided
  // The waiting task goes back to the front of the queue (`outcome`, `reason`), and next().
  void requeue_waiting(Outcome outcome, const std::string& reason);
  void go_to_dock(JourneyPurpose purpose);
  void start_trip(JourneyPurpose purpose, map::NodeIndex to);  // an own journey (trip_)
  // Traffic (executor_traffic.cpp; docs/traffic.md): parked when it stands idle or waits for a
  // task's window; asked to make way, it interrupts the wait and drives aside. Its stops, the
  // running task's (committed) and the planned ones, published for the others to plan around.
  void update_parked();
  void make_way(const traffic::MakeWay& make_way);
  void publish_stops();
  // Another robot's committed stop came or went at `node`: a wait for a task there is decided again.
  void stops_changed(map::NodeIndex node);
  void trip_ended(StepEnd end);
  void look_again_at(Time at);
  void preempt_for(Outcome outcome, const std::string& reason, std::vector<TaskId> then_schedule);
  void requeue_preempted(const TaskId& id, Outcome outcome, const std::string& reason);
  // The run hand_back_running() stopped has ended: the task is queued (or failed, past its window)
  // and, queued, `handed` gets it from the clock.
  void hand_back(const TaskId& id, const TaskEnd& e, std::function<void(const TaskId&)> handed);
  // A way the task needs was found blocked (ExecutorOptions::BlockedEdge::kWait): it is not
  // scheduled before the edge is likely passable again; false when that is not before its latest
  // start, or for an on-demand task not within `on_demand_patience` of its request (the caller
  // fails it). With `leave_at` (found before leaving: NavigateStep), it waits until then.
  bool hold_back(const TaskId& id, map::EdgeIndex edge, std::optional<Time> leave_at);
  // The first slot start after now, up to `until`, at which the live model holds `edge` likely
  // passable (kLikelyPassable), with its probability then.
  std::optional<std::pair<Time, double>> passable_again(map::EdgeIndex edge, Time until) const;
  // A held on-demand task goes back to the front of its queue and is due at its retry time.
  void hold_on_demand(const TaskId& id, Outcome outcome, const std::string& reason);
  // An on-demand task goes back to the front of its queue.
  void requeue_on_demand(const TaskId& id, Outcome outcome, const std::string& reason);
  void on_demand_due();  // a held on-demand task may run now: as if it had just come in
  // Frees the run or the trip later: it ended in a callback of its own, still on the stack.
  void retire_run();
  void retire_trip();

  // scheduling (executor_scheduling.cpp)
  void reschedule(std::vector<TaskId> new_ids, const std::string& why);
  void apply_schedule(const std::vector<TaskId>& ids, const PlannedAnswer& answer, const std::string& why);
  // The charges of a new schedule, for the dispatcher (noted when they moved).
  void apply_charges(const std::vector<TaskId>& ids, const PlannedAnswer& answer, const std::string& why);
  // The deferred tasks that can still meet their windows (the others end dropped, for good).
  std::vector<TaskId> reoffer_deferred();
  // reschedule() in two halves: the problem from the book (nothing when there is nothing to
  // solve), and the scheduler's answer carried out.
  // `held_over` (background scheduling): the new tasks beyond options_.background_offered, left
  // out of this problem for the next one.
  std::optional<ScheduleCall> prepare_schedule(std::vector<TaskId>& new_ids, const std::string& why,
                                               std::vector<TaskId>* held_over = nullptr);
  void finish_schedule(const std::vector<TaskId>& ids, std::vector<TaskId> new_ids,
                       const PlannedAnswer& answer, const std::string& why);

  // background scheduling (executor_background.cpp; options_.background_scheduling)
  struct Background;
  struct BackgroundDeleter {
    void operator()(Background* b) const;
  };
  void reschedule_in_background(std::vector<TaskId> new_ids, const std::string& why);
  void launch_background();
  void background_answered(ScheduleAnswer answer);
  void background_book_changed();  // a change that an answer in flight does not cover

  // deliveries (executor_deliveries.cpp)
  // Drops whose pickup ended without the object fail too, and an object on board with no drop
  // pending gets a return task (once per job).
  std::vector<TaskId> settle_jobs();  // the returns it made: new tasks to schedule
  std::vector<OnBoard> on_board_when_free() const;  // after the running task
  // A cancelled delivery task whose object is not on board takes the rest of its job with it.
  void cancel_job_of(const TaskId& id, const std::string& why);

  // assumptions and opportunities (executor_observations.cpp)
  void after_schedule(const std::string& why);  // records what the new plan assumes
  // Under risk_alpha, with tasks dropped for now: a reschedule at the next slot start.
  void offer_again_at_next_slot();
  void note_look_alikes();                      // why look-alike jobs do not interleave
  bool blocked(const TaskId& id) const;         // waits for its door: kept out of the schedule
  bool can_wait(const TaskId& id) const;        // may be blocked by a door seen closed
  // Blocks the task until `wait.door` is seen open (stored; timers for its retry and its end).
  void wait_for_door(const TaskId& id, const DoorWait& wait);
  void unblock(const TaskId& id);
  std::string seen_from(const Observation& seen) const;  // the robot's node, or the sensor
  void door_seen_closed(const Observation& seen);
  void door_seen_open(const Observation& seen);
  // Whether running `id` now (interrupting the running task) or right after the running task
  // leaves every planned task, and the other tasks of `with` (back from waiting), its window;
  // `why_not` says which would not fit.
  bool opportunity_fits(const TaskId& id, bool interrupt, const std::vector<TaskId>& with, std::string& why_not);
  // `serial`: the block the timer was set for (a later block of the same task has its own).
  void blocked_until_deadline(const TaskId& id, std::uint64_t serial);
  // A blocked task's retry when its door is likely open (learned), before its latest start.
  void place_retry(const TaskId& id, const std::string& door, Time latest, std::uint64_t serial);
  void retry_blocked(const TaskId& id, std::uint64_t serial);

  Building& building_;
  // The building's parts, by the names the executor's files use.
  Clock& clock_;
  Robot& robot_;
  const map::TopoMap& map_;
  store::Store& store_;
  const TimeZone& zone_;
  ExecutorOptions options_;
  plan::LearnedEdgeModels& models_;
  plan::TravelPlanner& planner_;
  TravelCache& travel_;
  // The snapshot read offline, only for NavigationRecord::offline_expected, and the cache that
  // reads it (the live one when the online model is off: it reads the snapshot itself).
  plan::LearnedEdgeModels& offline_models_;
  TravelCache& offline_travel_;
  std::unique_ptr<schedule::Scheduler> scheduler_;
  std::mt19937_64 rng_;

  TaskBook& book_;
  std::unique_ptr<Dispatcher> dispatcher_;
  std::unique_ptr<Deliveries> deliveries_;
  LoadingTimes& loading_;
  ExecutorStats stats_;
  std::vector<NavigationRecord> navigations_;
  bool in_fault_ = false;
  FoundBlocked& found_blocked_;  // what journeys found of the edges (steps_ holds it)
  std::unique_ptr<TrafficLink> traffic_;  // its end of the building's reservations; outlives the steps
  std::optional<traffic::BookingRobot> booking_;                  // its place in the building's bookings (plan around)
  std::optional<std::pair<TaskId, traffic::Booking>> committed_;  // the running task's stop, as set out
  std::vector<map::NodeIndex> stops_changed_at_;                  // nodes told of since the last look
  TimerId stops_look_ = 0;                                        // that look
  StepContext steps_;  // what every step works with

  std::unique_ptr<TaskRun> run_;        // the task waited for, navigated to or acted on
  std::unique_ptr<NavigateStep> trip_;  // the executor's own trip to the dock
  std::vector<std::unique_ptr<Step>> retired_steps_;  // ended in a callback still on the stack:
  std::vector<std::unique_ptr<TaskRun>> retired_runs_;  //   freed at the next robot callback
  std::optional<TaskId> confirmed_;                     // its running action was confirmed: its cancel counts as done
  std::vector<TaskId> after_preempt_;   // new tasks to schedule once the preempted task is out
  std::function<void(const TaskId&)> handing_back_;  // hand_back_running(): called once the run ended
  TimerId look_again_ = 0;              // idle: look again at the queues then
  TimerId offer_again_ = 0;             // offer_again_at_next_slot()
  std::optional<RobotFault> fault_;
  std::optional<Time> fault_since_;
  bool started_ = false;
  bool out_of_service_ = false;  // set_out_of_service(): next() starts nothing
  std::function<void()> unable_;        // on_unable()
  std::function<void(const std::vector<TaskId>&)> dropped_;  // on_dropped()
  std::function<void()> free_;                               // on_free()
  std::function<void(const TaskId&)> preempted_;             // on_preempted()
  std::unique_ptr<Charging> charging_;  // the battery: readings, thresholds, charges
  // assumptions and opportunities
  std::unique_ptr<AssumptionMap> assumption_map_;
  std::vector<Assumption> assumptions_;
  std::unique_ptr<Opportunities> opportunities_;
  AssumptionStats assumption_stats_;
  std::optional<std::string> broken_;   // the next schedule's event says what the break changed
  std::vector<TaskId> plan_before_break_;
  std::string look_alikes_;  // the last look-alike note
  DoorModels& door_models_;
  std::unique_ptr<Background, BackgroundDeleter> background_;  // last: its worker goes first
};

}  // namespace rondo::exec
