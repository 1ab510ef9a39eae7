// The executor's bookkeeping: accepting tasks, state transitions written to the store, start-up.
#include "rondo/exec/executor.h"

#include <fmt/format.h>

#include <algorithm>
#include <set>
#include <utility>

#include "rondo/core/task_codec.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/store/task_events.h"
#include "rondo/store/task_table.h"

namespace rondo::exec {

Executor::Executor(Clock& clock, Robot& robot, const map::TopoMap& map, store::Store& store, const TimeZone& zone,
                   ExecutorOptions options)
    : clock_(clock),
      robot_(robot),
      map_(map),
      store_(store),
      zone_(zone),
      options_(options),
      models_(std::make_shared<plan::LearnedEdgeModels>(map, nullptr)),
      rng_(options.seed) {
  planner_ = std::make_unique<plan::TravelOracle>(map_, models_, plan::TravelOracleOptions{.slot_width = options_.slot_width});
  travel_ = std::make_unique<TravelCache>(map_, models_, *planner_, options_.slot_width);
  robot_.set_listener(this);
}

Executor::~Executor() { robot_.set_listener(nullptr); }

std::string Executor::fmt_time(Time t) const {
  const Duration tod = zone_.time_of_day(t);
  return format_time_of_day(std::chrono::floor<std::chrono::minutes>(tod));
}

Status Executor::accept(const Task& task) {
  if (auto ok = validate(task, "task " + task.id); !ok) return ok;
  if (tasks_.contains(task.id)) return Error::invalid(fmt::format("task {}: the id is already taken", task.id));
  for (const std::string* node : {&task.start_node, &task.end_node}) {
    if (!node->empty() && !map_.find_node(*node))
      return Error::invalid(fmt::format("task {}: node '{}' is not on the map", task.id, *node));
  }
  if (task.kind == TaskKind::kStandard && task.start_node.empty())
    return Error::invalid(fmt::format("task {}: a standard task needs a start node", task.id));
  return Status{};
}

Result<std::vector<TaskId>> Executor::insert_tasks(std::vector<Task> tasks, std::string_view source) {
  std::set<TaskId> ids;
  for (const Task& t : tasks) {
    if (auto ok = accept(t); !ok) return ok.error();
    if (!ids.insert(t.id).second) return Error::invalid(fmt::format("task {}: the id appears twice", t.id));
  }
  // All or nothing: a batch the store refuses (or cannot write) leaves no task behind, in the store
  // or in memory, so the caller can send it again.
  const Time now = clock_.now();
  const std::string reason = fmt::format("added by {}", source);
  std::vector<store::TaskRecord> records;
  records.reserve(tasks.size());
  for (const Task& t : tasks) {
    records.push_back(
        {.id = t.id, .task = encode(t), .state = to_string(TaskState::kQueued), .created = now, .updated = now});
  }
  if (auto ok = store::add_tasks(store_, records, reason); !ok) return ok.error();
  std::vector<TaskId> standard;
  for (Task& t : tasks) {
    const TaskId id = t.id;
    const bool on_demand = t.kind == TaskKind::kOnDemand;
    tasks_.emplace(id, TaskRecord{.task = std::move(t), .state = TaskState::kQueued, .reason = reason,
                                  .source = std::string(source), .added = now});
    order_.push_back(id);
    if (on_demand)
      on_demand_.push_back(id);
    else
      standard.push_back(id);
  }
  return standard;
}

Status Executor::add_tasks(std::vector<Task> tasks, std::string_view source) {
  RONDO_ASSIGN_OR_RETURN(std::vector<TaskId> standard, insert_tasks(std::move(tasks), source));
  if (!started_) return Status{};  // start() schedules everything added before it
  if (!standard.empty()) reschedule(std::move(standard), "new tasks");
  if (!on_demand_.empty() && current_ && tasks_.at(*current_).task.kind == TaskKind::kStandard &&
      (phase_ == Phase::kNavigating || phase_ == Phase::kActing)) {
    const TaskId& od = on_demand_.front();
    if (interruptible_now()) {
      preempt_for(fmt::format("preempted by an on-demand task: {}", od), {});
      return Status{};
    }
    note(od, "waiting", fmt::format("the running task {} cannot be interrupted now; runs right after it", *current_));
  }
  kick();
  return Status{};
}

void Executor::add_routines(std::vector<Routine> routines) {
  for (Routine& r : routines) routines_.push_back(std::move(r));
}

void Executor::start() {
  if (started_) return;
  started_ = true;
  robot_interruptible_ = true;
  create_routine_tasks(zone_.local_date(clock_.now()));
  std::vector<TaskId> pending;
  for (const TaskId& id : order_)
    if (tasks_.at(id).task.kind == TaskKind::kStandard && tasks_.at(id).state == TaskState::kQueued &&
        std::find(schedule_.begin(), schedule_.end(), id) == schedule_.end())
      pending.push_back(id);
  if (!pending.empty()) reschedule(std::move(pending), "start");
  schedule_midnight();
  schedule_refit();
  clock_.schedule_at(clock_.now(), [this] { kick(); });
}

void Executor::transition(const TaskId& id, TaskState state, const std::string& reason) {
  TaskRecord& r = tasks_.at(id);
  r.state = state;
  r.reason = reason;
  if (is_final(state)) r.ended = clock_.now();
  // The store is the record of what happened: a failed write is reported, the run goes on.
  if (auto ok = store::set_task_state(store_, id, to_string(state), clock_.now(), reason); !ok)
    write_errors_.push_back(ok.error().message);
}

void Executor::note(const TaskId& id, const std::string& event, const std::string& reason) {
  if (auto ok = store::append_task_event(store_, {.time = clock_.now(), .task_id = id, .event = event, .reason = reason});
      !ok)
    write_errors_.push_back(ok.error().message);
}

bool Executor::interruptible_now() const {
  if (!current_) return true;
  return tasks_.at(*current_).task.interruptible && robot_interruptible_;
}

}  // namespace rondo::exec
