// The executor (MISSION.md §3): keeps the tasks, schedules them, runs them through the robot,
// watches them and reacts. Event-driven on an injected Clock: it never sleeps and never reads the
// wall clock, so the same code runs a simulated robot for weeks in seconds and a real one in real
// time.
//
//   Executor ex(clock, robot, map, store, zone, {.dock = *map.find_node("ChargingPoint")});
//   ex.add_routines(routines);                 // tasks for every day, created ahead of their windows
//   ex.start();                                // posts the day's first events
//   ex.add_task(task, "api");                  // standard: trySchedule; on-demand: runs at once
//   clock.run_until(end);
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
// - idle: back to the dock. Nightly (at `refit_at`, local time) the edge models are refitted
//   from the whole traversal log, so travel estimates and schedules adapt.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/routine.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/map_travel.h"
#include "rondo/exec/outcome.h"
#include "rondo/exec/robot.h"
#include "rondo/exec/task_book.h"
#include "rondo/learn/edge_models.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/travel_oracle.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/store/store.h"

namespace rondo::exec {

struct ExecutorOptions {
  map::NodeIndex dock = 0;
  double navigation_overrun = 2.0;       // preempt navigation past this x expected travel + slack
  Duration navigation_slack = seconds(60);
  double action_overrun = 1.5;           // preempt actions past this x processing time + slack
  Duration action_slack = seconds(30);
  Duration dock_when_waiting_over = minutes(15);  // longer waits are spent on the charger
  int max_failed_edges = 25;             // a navigation gives up after this many failed attempts
  std::optional<Duration> refit_at = hours(2);    // local time of day; nothing = never refit
  int duration_bins = 24;                // time-of-day bins of the refitted travel-time models
  Duration slot_width = minutes(15);     // travel-time slots of the planner
  std::int64_t scheduler_polls = 20'000;  // deterministic budget of each scheduler call (docs/scheduling.md)
  std::uint64_t seed = 1;                // ties in dropping
  std::string robot_name = "robot";      // the robot's row in the store's robot_state
};

// Figures of the run so far, for the report.
struct ExecutorStats {
  int navigation_attempts = 0;
  int navigation_successes = 0;
  Duration travelling{0};  // edge attempts
  Duration acting{0};      // actions
  Duration waiting{0};     // waiting for a window to open
  Duration busy{0};        // a task in progress: its travel, waiting and actions
  int refits = 0;
  int schedules = 0;       // scheduler calls
};

// One navigation of a task to its start: what the executor expected when it left, and what
// happened. The travel-estimate error of a run is read from these.
struct NavigationRecord {
  TaskId task;
  Time start{};
  Duration expected{0};
  Duration actual{0};
  bool arrived = false;
};

class Executor final : public RobotListener {
 public:
  // Precondition: `dock` is a node of `map`; clock, robot, map and store outlive the executor.
  Executor(Clock& clock, Robot& robot, const map::TopoMap& map, store::Store& store, const TimeZone& zone,
           ExecutorOptions options);
  ~Executor() override;
  Executor(const Executor&) = delete;
  Executor& operator=(const Executor&) = delete;

  // Accepts tasks (committed to the store before this returns), then schedules them together.
  // kInvalidInput for a task that cannot be run here (unknown node, no window, duplicate id, an
  // id the store already holds), kStorage when the store cannot write; either way nothing is added.
  Status add_tasks(std::vector<Task> tasks, std::string_view source);
  Status add_task(Task task, std::string_view source) { return add_tasks({std::move(task)}, source); }
  // Cancels a task: a queued (or waiting, or dropped-for-now) one ends `cancelled` at once; a
  // running one is stopped through the robot's cancel() when it is interruptible now, else at its
  // next interruptible moment (a `cancel pending` event says so). kNotFound for an unknown task,
  // kConflict for one already in a final state.
  Status cancel_task(const TaskId& id, const std::string& reason);
  // Routines become tasks every day at local midnight (and at start() for the current day).
  void add_routines(std::vector<Routine> routines);
  // Posts the first events: today's routine tasks, the nightly refit, and the first dispatch.
  void start();

  const std::map<TaskId, TaskRecord>& tasks() const { return book_.records(); }
  const std::vector<TaskId>& task_order() const { return book_.order(); }  // in the order added
  const TaskBook& book() const { return book_; }
  const ExecutorStats& stats() const { return stats_; }
  const std::vector<NavigationRecord>& navigations() const { return navigations_; }
  // Store writes that failed (the run goes on; the caller reports them).
  const std::vector<std::string>& write_errors() const { return book_.write_errors(); }
  const plan::LearnedEdgeModels& models() const { return *models_; }

  // RobotListener
  void on_edge_finished(const EdgeAttempt& attempt) override;
  void on_action_finished(const ActionResult& result) override;
  void on_interruptible_changed(bool interruptible) override;
  void on_observation(const Observation& observation) override;
  void on_fault(const RobotFault& fault) override;
  void on_ready() override;
  bool paused() const { return fault_.has_value(); }

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
  const std::vector<Routine>& routines() const { return routines_; }
  // Adds a routine while running: today's instances that can still be met are added at once.
  // kInvalidInput for a name already taken or a node not on the map.
  Status add_routine_now(Routine routine);
  // Forgets a routine: no more instances from the next day on (today's stay). kNotFound if unknown.
  Status remove_routine(const std::string& name);

 private:
  enum class Phase { kIdle, kWaiting, kNavigating, kActing, kDocking };
  enum class CancelIntent { kNone, kNavigationOverrun, kActionOverrun, kPreempt, kCancel, kLeaveDockTrip };

  // bookkeeping (executor.cpp)
  Status accept(const Task& task);
  // Validates, stores (all or nothing) and records tasks; returns the standard ones (on-demand ones
  // are queued).
  Result<std::vector<TaskId>> insert_tasks(std::vector<Task> tasks, std::string_view source);
  void log_battery();
  // The robot's last known state in the store (its node, pose, battery, fault), for a restart.
  void save_robot_state();
  bool interruptible_now() const;
  std::string fmt_time(Time t) const;

  // scheduling (executor_scheduling.cpp)
  void reschedule(std::vector<TaskId> new_ids, const std::string& why);
  void apply_schedule(const std::vector<TaskId>& ids, const schedule::Schedule& s, const std::string& why);
  std::pair<map::NodeIndex, Time> free_at() const;  // where and when the robot is next free

  // running (executor_running.cpp)
  void kick();  // reconsider what to do now
  void next();
  void start_task(const TaskId& id);
  void begin_navigation(map::NodeIndex target, Duration expected);
  void step_navigation();
  void abandon_navigation(Outcome outcome, const std::string& reason);
  std::vector<map::EdgeIndex> expected_route(const plan::Policy& policy, map::NodeIndex from) const;
  void arrived();
  void start_actions();
  void run_next_action();
  void finish_task(TaskState state, Outcome outcome, const std::string& reason);
  // Starts the navigation or action monitor: it fires past factor x expected + slack.
  TimerId arm_monitor(CancelIntent why, const char* what, const char* of, Duration expected, double factor,
                      Duration slack);
  void monitor_fired(CancelIntent why, const std::string& reason);
  void handle_cancelled();
  void go_to_dock();
  void clear_timers();
  void preempt_for(Outcome outcome, const std::string& reason, std::vector<TaskId> then_schedule);
  void stop_current(CancelIntent intent, Outcome outcome, const std::string& reason);
  void requeue_preempted(const TaskId& id, Outcome outcome, const std::string& reason);
  // The deferred tasks that can still meet their windows (the others end dropped, for good).
  std::vector<TaskId> reoffer_deferred();
  void suspend_monitors();
  void resume_monitors();

  // daily (executor_daily.cpp)
  void create_routine_tasks(std::chrono::year_month_day day);
  void schedule_midnight();
  void schedule_refit();
  void refit();

  Clock& clock_;
  Robot& robot_;
  const map::TopoMap& map_;
  store::Store& store_;
  TimeZone zone_;
  ExecutorOptions options_;
  std::shared_ptr<plan::LearnedEdgeModels> models_;
  std::unique_ptr<plan::TravelOracle> planner_;
  std::unique_ptr<TravelCache> travel_;
  schedule::DefaultScheduler solver_;
  std::mt19937_64 rng_;

  TaskBook book_;
  std::vector<Routine> routines_;
  std::vector<TaskId> schedule_;        // standard tasks to run, in planned order
  std::deque<TaskId> on_demand_;        // on-demand tasks waiting for the running one to end
  std::vector<TaskId> deferred_;        // dropped for now: offered again at every reschedule
  std::optional<std::string> cancel_pending_;  // cancel the running task at its next interruptible moment

  Phase phase_ = Phase::kIdle;
  std::optional<TaskId> current_;       // the task being waited for, navigated to or acted on
  map::NodeIndex nav_target_ = 0;
  Time nav_start_{};
  Duration nav_expected_{0};
  int failed_edges_ = 0;
  std::size_t action_index_ = 0;
  Time acting_start_{};
  Time wait_start_{};
  bool robot_interruptible_ = true;
  CancelIntent cancel_intent_ = CancelIntent::kNone;
  Outcome cancel_outcome_ = Outcome::kNone;
  std::string cancel_reason_;
  std::optional<std::pair<CancelIntent, std::string>> overrun_pending_;  // monitor fired while not interruptible
  std::vector<TaskId> after_cancel_schedule_;  // new tasks to schedule once the preempted task is out
  TimerId wait_timer_ = 0, nav_monitor_ = 0, action_monitor_ = 0;
  struct MonitorDue {
    Time at{};                     // when the armed monitor fires
    std::string reason;            // what it says then
    std::optional<Duration> left;  // set while suspended: the time it still had
  };
  MonitorDue nav_due_, action_due_;   // when each armed monitor fires, and what it says
  std::optional<RobotFault> fault_;   // dispatch and monitors stand still while set
  std::optional<Time> fault_since_;
  ExecutorStats stats_;
  std::vector<NavigationRecord> navigations_;
  bool started_ = false;
};

}  // namespace rondo::exec
