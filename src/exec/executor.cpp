// The executor's bookkeeping: accepting tasks, state transitions written to the store, start-up.
#include "rondo/exec/executor.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "rondo/plan/distance_prior.h"
#include "rondo/store/events.h"
#include "rondo/store/observations.h"
#include "rondo/store/robot_state.h"

namespace rondo::exec {

Executor::Executor(Clock& clock, Robot& robot, const map::TopoMap& map, store::Store& store, const TimeZone& zone,
                   ExecutorOptions options)
    : clock_(clock),
      robot_(robot),
      map_(map),
      store_(store),
      zone_(zone),
      options_(options),
      models_(std::make_shared<plan::LearnedEdgeModels>(map, nullptr, plan::DistancePriorOptions{},
                                                        options.online_model
                                                            ? plan::LearnedEdgeModels::Reading::kOnline
                                                            : plan::LearnedEdgeModels::Reading::kOffline)),
      offline_models_(std::make_shared<plan::LearnedEdgeModels>(map, nullptr)),
      rng_(options.seed),
      book_(store, clock) {
  planner_ = std::make_unique<plan::TravelOracle>(map_, models_, plan::TravelOracleOptions{.slot_width = options_.slot_width});
  travel_ = std::make_unique<TravelCache>(map_, models_, *planner_, options_.slot_width);
  offline_planner_ = std::make_unique<plan::TravelOracle>(map_, offline_models_,
                                                          plan::TravelOracleOptions{.slot_width = options_.slot_width});
  offline_travel_ = std::make_unique<TravelCache>(map_, offline_models_, *offline_planner_, options_.slot_width);
  robot_.set_listener(this);
}

Executor::~Executor() { robot_.set_listener(nullptr); }

std::string Executor::fmt_time(Time t) const { return zone_.format_clock(t); }

Status Executor::accept(const Task& task) {
  if (auto ok = validate(task, "task " + task.id); !ok) return ok;
  if (book_.contains(task.id)) return Error::invalid(fmt::format("task {}: the id is already taken", task.id));
  for (const std::string* node : {&task.start_node, &task.end_node}) {
    if (!node->empty() && !map_.find_node(*node))
      return Error::invalid(fmt::format("task {}: node '{}' is not on the map", task.id, *node));
  }
  if (task.kind == TaskKind::kStandard && task.start_node.empty())
    return Error::invalid(fmt::format("task {}: a standard task needs a start node", task.id));
  return Status{};
}

Result<std::vector<TaskId>> Executor::insert_tasks(std::vector<Task> tasks, std::string_view source) {
  for (const Task& t : tasks) RONDO_RETURN_IF_ERROR(accept(t));
  std::vector<TaskId> ids;
  for (const Task& t : tasks) ids.push_back(t.id);
  RONDO_RETURN_IF_ERROR(book_.add(std::move(tasks), source));
  std::vector<TaskId> standard;
  for (const TaskId& id : ids) {
    if (book_.at(id).task.kind == TaskKind::kOnDemand)
      on_demand_.push_back(id);
    else
      standard.push_back(id);
  }
  return standard;
}

Status Executor::add_tasks(std::vector<Task> tasks, std::string_view source) {
  std::string ids;
  for (const Task& t : tasks) ids += (ids.empty() ? "" : ",") + t.id;
  auto inserted = insert_tasks(std::move(tasks), source);
  if (!inserted) {
    // A refused request is part of the record too.
    book_.note_request(ids, "rejected", Outcome::kInvalidRequest,
                       fmt::format("from {}: {}", source, inserted.error().message));
    return inserted.error();
  }
  std::vector<TaskId> standard = std::move(*inserted);
  if (!started_) return Status{};  // start() schedules everything added before it
  if (!standard.empty()) reschedule(std::move(standard), "new tasks");
  if (!on_demand_.empty() && current_ && book_.at(*current_).task.kind == TaskKind::kStandard &&
      (phase_ == Phase::kNavigating || phase_ == Phase::kActing)) {
    const TaskId& od = on_demand_.front();
    if (interruptible_now()) {
      preempt_for(Outcome::kPreemptedOnDemand, fmt::format("preempted by an on-demand task: {}", od), {});
      return Status{};
    }
    book_.note(od, "waiting", Outcome::kRunsAfterCurrent,
         fmt::format("the running task {} cannot be interrupted now; runs right after it", *current_));
  }
  kick();
  return Status{};
}

Status Executor::cancel_task(const TaskId& id, const std::string& reason) {
  if (!book_.contains(id)) return Error::not_found(fmt::format("no task '{}'", id));
  const TaskRecord& r = book_.at(id);
  if (is_final(r.state))
    return Error{ErrorCode::kConflict, fmt::format("task {} is already {}: it cannot be cancelled", id, to_string(r.state))};
  const std::string why = reason.empty() ? "cancelled" : "cancelled: " + reason;
  if (current_ && *current_ == id) {
    if (phase_ == Phase::kWaiting) {
      clock_.cancel(wait_timer_);
      wait_timer_ = 0;
      stats_.waiting += clock_.now() - wait_start_;
      current_.reset();
      phase_ = Phase::kIdle;
    } else if (interruptible_now()) {
      stop_current(CancelIntent::kCancel, Outcome::kCancelled, why);
      return Status{};
    } else {
      cancel_pending_ = why;
      book_.note(id, "cancel pending", Outcome::kCancelPending,
                 why + "; the task cannot be interrupted now, so it stops at its next interruptible moment");
      return Status{};
    }
  }
  std::erase(schedule_, id);
  std::erase(deferred_, id);
  std::erase(on_demand_, id);
  book_.at(id).planned_start.reset();
  book_.at(id).planned_end.reset();
  book_.transition(id, TaskState::kCancelled, Outcome::kCancelled, why);
  if (started_) {
    reschedule({}, "task " + id + " cancelled");  // its room may let a dropped task back in
    kick();
  }
  return Status{};
}

void Executor::add_routines(std::vector<Routine> routines) {
  for (Routine& r : routines) routines_.push_back(std::move(r));
}

void Executor::start() {
  if (started_) return;
  started_ = true;
  robot_interruptible_ = true;
  if (auto up = robot_.activate(); !up) on_fault({.kind = RobotFault::Kind::kError, .message = up.error().message});
  create_routine_tasks(zone_.local_date(clock_.now()));
  std::vector<TaskId> pending;
  for (const TaskId& id : book_.order())
    if (book_.at(id).task.kind == TaskKind::kStandard && book_.at(id).state == TaskState::kQueued &&
        std::find(schedule_.begin(), schedule_.end(), id) == schedule_.end())
      pending.push_back(id);
  if (!pending.empty()) reschedule(std::move(pending), "start");
  schedule_midnight();
  schedule_refit();
  clock_.schedule_at(clock_.now(), [this] { kick(); });
}

void Executor::log_battery() {
  const store::Observation o{.what = "battery", .where = map_.node(robot_.location()).name, .when = clock_.now(),
                             .value = std::clamp(robot_.battery(), 0.0, 1.0), .text = std::nullopt};
  if (auto ok = store::add_observation(store_, o); !ok) book_.write_error(ok.error().message);
}

void Executor::save_robot_state() {
  const std::optional<map::Pose> pose = robot_.position();
  store::RobotState st{.robot = options_.robot_name,
                       .node = map_.node(robot_.location()).name,
                       .battery = std::clamp(robot_.battery(), 0.0, 1.0),
                       .updated = clock_.now()};
  if (pose) {
    st.x = pose->x;
    st.y = pose->y;
    st.yaw = pose->yaw;
  }
  if (fault_) st.fault = fault_->message;
  if (auto ok = store::save_robot_state(store_, st); !ok) book_.write_error(ok.error().message);
}

void Executor::on_observation(const Observation& seen) {
  const store::Observation o{.what = seen.what, .where = seen.where, .when = seen.when, .value = seen.value,
                             .text = seen.text.empty() ? std::nullopt : std::optional<std::string>(seen.text)};
  if (auto ok = store::add_observation(store_, o); !ok) book_.write_error(ok.error().message);
}

void Executor::on_fault(const RobotFault& fault) {
  const bool first = !fault_;
  fault_ = fault;
  if (!first) return;
  fault_since_ = clock_.now();
  save_robot_state();
  book_.note_robot("fault", Outcome::kRobotFault, fmt::format("{}: {}; dispatch paused", to_string(fault.kind), fault.message));
  suspend_monitors();
  if (wait_timer_ != 0 && phase_ == Phase::kIdle) {  // an idle look-again timer: ready() kicks instead
    clock_.cancel(wait_timer_);
    wait_timer_ = 0;
  }
}

void Executor::on_ready() {
  if (!fault_) return;
  const Duration down = clock_.now() - fault_since_.value_or(clock_.now());
  fault_.reset();
  fault_since_.reset();
  book_.note_robot("ready", Outcome::kRobotReady,
             fmt::format("ready again after {}; dispatch resumes",
                         format_duration(std::chrono::round<std::chrono::seconds>(down))));
  resume_monitors();
  if (phase_ == Phase::kNavigating || phase_ == Phase::kDocking) {
    if (!robot_.busy()) step_navigation();
    return;
  }
  if (phase_ == Phase::kActing) {
    if (!robot_.busy()) run_next_action();
    return;
  }
  kick();
}

bool Executor::interruptible_now() const {
  if (!current_) return true;
  return book_.at(*current_).task.interruptible && robot_interruptible_;
}

}  // namespace rondo::exec
