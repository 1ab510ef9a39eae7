// The executor's front: accepting and cancelling tasks, start-up, and what it tells about itself.
#include "rondo/exec/executor.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "assumptions.h"
#include "charge_planning.h"
#include "charging.h"
#include "deliveries.h"
#include "dispatcher.h"
#include "door_models.h"
#include "found_blocked.h"
#include "loading_times.h"
#include "opportunities.h"
#include "rondo/learn/weekly_memory.h"
#include "rondo/map/map_geometry.h"
#include "rondo/schedule/default_scheduler.h"
#include "scheduling.h"
#include "task_run.h"
#include "traffic_link.h"

namespace rondo::exec {

const char* to_string(ExecutorPhase phase) {
  switch (phase) {
    case ExecutorPhase::kIdle: return "idle";
    case ExecutorPhase::kWaiting: return "waiting";
    case ExecutorPhase::kNavigating: return "navigating";
    case ExecutorPhase::kActing: return "acting";
    case ExecutorPhase::kDocking: return "docking";
  }
  return "idle";
}

Executor::Executor(Building& building, Robot& robot, ExecutorOptions options,
                   std::unique_ptr<schedule::Scheduler> scheduler)
    : building_(building),
      clock_(building_.clock),
      robot_(robot),
      map_(building_.map),
      store_(building_.store),
      zone_(building_.zone),
      options_(options),
      models_(*building_.models),
      planner_(building_.planner),
      travel_(building_.travel),
      offline_models_(*building_.offline_models),
      // With the online model off the executor plans with the snapshot itself: no second cache.
      offline_travel_(options_.online_model ? building_.offline_travel : building_.travel),
      scheduler_(scheduler ? std::move(scheduler) : std::make_unique<schedule::DefaultScheduler>()),
      rng_(options.seed),
      book_(building_.book),
      dispatcher_(std::make_unique<Dispatcher>(map_, travel_, book_, options_, zone_, building_.spec_tasks.get())),
      deliveries_(std::make_unique<Deliveries>()),
      loading_(*building_.loading),
      found_blocked_(*building_.found_blocked),
      traffic_(building_.reservations ? std::make_unique<TrafficLink>(clock_, *building_.reservations,
                                                                      building_.traffic_waits, options_.robot_name)
                                      : nullptr),
      steps_{clock_,
             robot_,
             map_,
             book_,
             travel_,
             offline_travel_,
             planner_,
             options_,
             zone_,
             stats_,
             navigations_,
             in_fault_,
             models_,
             [this] { read_battery(); },
             found_blocked_,
             *building_.spec_tasks,
             building_.speeds,
             traffic_.get()},
      assumption_map_(std::make_unique<AssumptionMap>(map_, options_.dock)),
      opportunities_(std::make_unique<Opportunities>()),
      door_models_(*building_.door_models) {
  charging_ = std::make_unique<Charging>(ChargingContext{.map = map_,
                                                        .options = options_,
                                                        .clock = clock_,
                                                        .robot = robot_,
                                                        .book = book_,
                                                        .zone = zone_,
                                                        .travel = travel_,
                                                        .snapshot = offline_models_});
  robot_.set_listener(this);
  if (building_.bookings) {
    booking_ = building_.bookings->join(options_.robot_name);
    dispatcher_->plan_around(building_.bookings, *booking_);
    building_.bookings->on_changed(*booking_, [this](map::NodeIndex node) { stops_changed(node); });
  }
  if (options_.forget_finished)
    book_.forget_finished([this] { clock_.schedule_at(clock_.now(), [this] { sweep_finished(); }); });
}

// Finished tasks leave memory (the store keeps them), with what the executor kept about them.
void Executor::sweep_finished() {
  for (const TaskId& id : book_.sweep()) {
    opportunities_->unblock(id);
    std::erase(after_preempt_, id);
  }
  deliveries_->forget_settled(book_);
}

Executor::~Executor() {
  robot_.set_listener(nullptr);
  if (booking_) {
    building_.bookings->on_changed(*booking_, {});
    building_.bookings->publish(*booking_, {});
  }
  if (stops_look_ != 0) clock_.cancel(stops_look_);
  if (look_again_ != 0) clock_.cancel(look_again_);
  if (offer_again_ != 0) clock_.cancel(offer_again_);
}

std::optional<std::string> Executor::cannot_run(const std::vector<Action>& actions) const {
  return exec::cannot_run(robot_, actions);
}

void Executor::take(std::vector<TaskId> ids) {
  std::vector<TaskId> standard;
  for (const TaskId& id : ids) {
    deliveries_->add(book_.at(id).task);
    if (book_.at(id).task.kind == TaskKind::kOnDemand)
      dispatcher_->queue_on_demand(id);
    else
      standard.push_back(id);
  }
  if (!started_) return;  // schedule_restored() schedules everything given before it
  if (!standard.empty()) reschedule(std::move(standard), "new tasks");
  if (!give_way_to_on_demand()) kick();
}

bool Executor::give_way_to_on_demand() {
  const std::optional<TaskId> ready = dispatcher_->ready_on_demand(clock_.now());
  if (!ready || !running_standard()) return false;
  if (interruptible_now()) {
    preempt_for_on_demand(*ready);
    return true;
  }
  book_.note(*ready, EventKind::kWaitsForRunningTask, Outcome::kRunsAfterCurrent,
             fmt::format("the running task {} cannot be interrupted now; runs right after it", run_->id()));
  return false;
}

Status Executor::cancel_task(const TaskId& id, const std::string& reason) {
  const std::optional<TaskState> state = book_.state_of(id);
  if (!state) return Error::not_found(fmt::format("no task '{}'", id));
  if (is_final(*state))
    return Error{ErrorCode::kConflict,
                 fmt::format("task {} is already {}: it cannot be cancelled", id, to_string(*state))};
  const std::string why = reason.empty() ? "cancelled" : "cancelled: " + reason;
  if (run_ && run_->id() == id) {
    if (run_->waiting()) {
      end_wait();
    } else if (interruptible_now()) {
      run_->stop(TaskRun::Stop::kCancel, Outcome::kCancelled, why);
      return Status{};
    } else {
      run_->cancel_when_possible(why);
      book_.note(id, EventKind::kCancelPending, Outcome::kCancelPending,
                 why + "; the task cannot be interrupted now, so it stops at its next interruptible moment");
      return Status{};
    }
  }
  dispatcher_->forget(id);
  book_.at(id).planned_start.reset();
  book_.at(id).planned_end.reset();
  book_.transition(id, TaskState::kCancelled, Outcome::kCancelled, why);
  cancel_job_of(id, why);
  if (started_) {
    reschedule({}, "task " + id + " cancelled");  // its room may let a dropped task back in
    kick();
  }
  return Status{};
}

void Executor::start() {
  if (started_) return;
  started_ = true;
  if (auto up = robot_.activate(); !up) on_fault({.kind = RobotFault::Kind::kError, .message = up.error().message});
  if (traffic_) {
    traffic_->join(robot_.location());
    traffic_->when_parked_asked([this](const traffic::MakeWay& m) { make_way(m); });
  }
  read_battery();
}

void Executor::schedule_restored() {
  std::vector<TaskId> pending;
  for (const TaskId& id : book_.order())
    if (book_.at(id).robot == name() && book_.at(id).task.kind == TaskKind::kStandard &&
        book_.at(id).state == TaskState::kQueued &&
        !book_.at(id).dropped_for_now &&  // deferred (restore): reschedule() offers them again
        !blocked(id) &&                   // waits for its door (restore)
        !dispatcher_->is_planned(id) && !dispatcher_->is_deferred(id))
      pending.push_back(id);
  if (!pending.empty()) reschedule(std::move(pending), "start");
}

void Executor::kick_soon() {
  clock_.schedule_at(clock_.now(), [this] { kick(); });
}

bool Executor::interruptible_now() const { return !run_ || run_->interruptible(); }

bool Executor::running_standard() const {
  return run_ && !run_->waiting() && run_->task().kind == TaskKind::kStandard;
}

void Executor::preempt_for_on_demand(const TaskId& id) {
  preempt_for(Outcome::kPreemptedOnDemand, fmt::format("preempted by an on-demand task: {}", id), {});
}

ExecutorPhase Executor::phase() const {
  if (run_) {
    if (run_->waiting()) return ExecutorPhase::kWaiting;
    return run_->acting_since() ? ExecutorPhase::kActing : ExecutorPhase::kNavigating;
  }
  return trip_ ? ExecutorPhase::kDocking : ExecutorPhase::kIdle;
}

std::optional<TaskId> Executor::current_task() const {
  if (run_) return run_->id();
  return std::nullopt;
}

std::optional<TaskId> Executor::preemptible_run() const {
  if (running_standard() && interruptible_now()) return run_->id();
  return std::nullopt;
}

}  // namespace rondo::exec
