// The service's additions to the executor (`rondo serve`, rondo::service): a read-only view of
// what it is doing, and the changes a person makes while it runs (a waiting task's window or
// priority, routines added and removed). Everything here runs on the clock's thread, like the
// rest of the executor; the HTTP threads reach it only through Clock::post().
#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "dispatcher.h"
#include "rondo/core/task_codec.h"
#include "rondo/exec/executor.h"
#include "rondo/store/task_table.h"
#include "task_run.h"

namespace rondo::exec {
Executor::Activity Executor::activity() const {
  Activity a;
  a.phase = to_string(phase());
  a.current = current_task();
  a.fault = fault_;
  a.planned = dispatcher_->planned();
  a.on_demand.assign(dispatcher_->on_demand().begin(), dispatcher_->on_demand().end());
  return a;
}

Status Executor::update_task(const TaskId& id, std::optional<TimeWindow> window, std::optional<int> priority) {
  const std::optional<TaskState> state = book_.state_of(id);
  if (!state) return Error::not_found(fmt::format("no task '{}'", id));
  if (is_final(*state)) return Error{ErrorCode::kConflict, fmt::format("task {} is already {}", id, to_string(*state))};
  TaskRecord& record = book_.at(id);
  if (record.state != TaskState::kQueued || current_task() == id)
    return Error{ErrorCode::kConflict,
                 fmt::format("task {} is {}: only a queued task can be changed", id, to_string(record.state))};
  Task changed = record.task;
  std::string what;
  if (window) {
    if (changed.kind == TaskKind::kOnDemand)
      return Error::invalid(fmt::format("task {}: window: an on-demand task has no window", id));
    changed.window = *window;
    what = fmt::format("window {} to {}", zone_.format_clock(window->release), zone_.format_clock(window->deadline));
  }
  if (priority) {
    changed.priority = *priority;
    what += fmt::format("{}priority {}", what.empty() ? "" : ", ", *priority);
  }
  if (auto ok = validate(changed, "task " + id); !ok) return ok;
  if (what.empty()) return Status{};
  RONDO_RETURN_IF_ERROR(store::set_task_definition(store_, id, encode(changed)));
  record.task = std::move(changed);
  book_.note(id, EventKind::kChanged, Outcome::kNone, "changed: " + what);
  if (record.task.kind == TaskKind::kOnDemand) return Status{};
  // Offered again as a new task, so that a change it no longer fits drops it (for now) with a
  // reason instead of breaking the plan of the others.
  dispatcher_->unplan(id);
  background_book_changed();  // an answer in flight still has the old window or priority
  const bool deferred = dispatcher_->is_deferred(id);
  if (started_)
    reschedule(deferred ? std::vector<TaskId>{} : std::vector<TaskId>{id}, fmt::format("task {} changed", id));
  if (started_) kick();
  return Status{};
}

Status Executor::add_routine_now(Routine routine) {
  for (const Routine& r : routines_)
    if (r.name == routine.name) return Error::invalid(fmt::format("routine '{}': the name is already taken", r.name));
  for (const std::string* node : {&routine.task.start_node, &routine.task.end_node})
    if (!node->empty() && !map_.find_node(*node))
      return Error::invalid(fmt::format("routine '{}': node '{}' is not on the map", routine.name, *node));
  if (auto why = cannot_run(robot_, routine.task.actions))
    return Error::invalid(fmt::format("routine '{}': {}", routine.name, *why));
  const std::string name = routine.name;
  routines_.push_back(std::move(routine));
  if (!started_) return Status{};
  std::vector<Task> batch;
  const Time now = clock_.now();
  for (Task& t : instances_on(routines_.back(), zone_.local_date(now), zone_))
    if (t.window && t.window->deadline - t.duration > now && !book_.known(t.id)) batch.push_back(std::move(t));
  if (batch.empty()) return Status{};
  if (auto ok = add_tasks(std::move(batch), "routine"); !ok) {
    routines_.pop_back();
    return ok;
  }
  kick();
  return Status{};
}

Status Executor::add_routines_now(std::vector<Routine> routines, const store::RequestTaken& taken,
                                  const std::string& why) {
  std::set<std::string> names;
  for (const Routine& r : routines_) names.insert(r.name);
  Status valid;
  if (routines.empty()) valid = Error::invalid("it holds no routine");
  for (const Routine& routine : routines) {
    if (!valid) break;
    if (!names.insert(routine.name).second)
      valid = Error::invalid(fmt::format("routine '{}': the name is already taken", routine.name));
    for (const std::string* node : {&routine.task.start_node, &routine.task.end_node})
      if (valid && !node->empty() && !map_.find_node(*node))
        valid = Error::invalid(fmt::format("routine '{}': node '{}' is not on the map", routine.name, *node));
    if (auto cannot = cannot_run(robot_, routine.task.actions); valid && cannot)
      valid = Error::invalid(fmt::format("routine '{}': {}", routine.name, *cannot));
  }
  if (!valid) {
    const store::RequestTaken refused{taken.id, taken.at, "rejected: " + valid.error().message};
    book_.note_request(fmt::format("request {}", taken.id), EventKind::kRejected, Outcome::kInvalidRequest, valid.error().message,
                       &refused);
    return valid;
  }
  // Marked taken with what keeps the routines: a kill after this finds them at the restart.
  RONDO_RETURN_IF_ERROR(book_.take_request(taken, EventKind::kRoutinesAdded, Outcome::kNone, why));
  const std::size_t first = routines_.size();
  for (Routine& r : routines) routines_.push_back(std::move(r));
  if (!started_) return Status{};  // start() adds today's instances
  std::vector<Task> batch;
  const Time now = clock_.now();
  for (std::size_t i = first; i < routines_.size(); ++i)
    for (Task& t : instances_on(routines_[i], zone_.local_date(now), zone_))
      if (t.window && t.window->deadline - t.duration > now && !book_.known(t.id)) batch.push_back(std::move(t));
  if (batch.empty()) return Status{};
  // A refusal here is in the event log; the routines stay (they are kept), and make tomorrow's.
  if (auto ok = add_tasks(std::move(batch), "routine"); !ok) book_.write_error(ok.error().message);
  kick();
  return Status{};
}

Status Executor::remove_routine(const std::string& name) {
  const auto it = std::find_if(routines_.begin(), routines_.end(), [&](const Routine& r) { return r.name == name; });
  if (it == routines_.end()) return Error::not_found(fmt::format("no routine '{}'", name));
  routines_.erase(it);
  return Status{};
}

void Executor::set_out_of_service(bool out, bool halt, const std::string& reason) {
  if (out == out_of_service_) return;
  out_of_service_ = out;
  const std::string why = reason.empty() ? "" : ": " + reason;
  if (!out) {
    book_.note_robot(options_.robot_name, EventKind::kBackInService, Outcome::kNone, "dispatch resumed" + why);
    if (started_) {
      reschedule({}, "back in service");
      kick();
    }
    return;
  }
  book_.note_robot(options_.robot_name, 
      EventKind::kOutOfService, Outcome::kNone,
      fmt::format("dispatch paused{}; {}", why, halt ? "the running task is halted" : "the running task finishes"));
  if (run_ && run_->waiting()) {  // not started yet: back to the head of the queue
    const TaskId id = run_->id();
    end_wait();
    book_.transition(id, TaskState::kQueued, Outcome::kScheduleChanged, "waiting ended: out of service");
    dispatcher_->put_first_in_plan(id);
  } else if (run_ && halt) {
    // Keeps its id and progress: requeue_preempted() puts it back in the queue.
    if (interruptible_now())
      preempt_for(Outcome::kInterrupted, "halted: out of service", {});
    else
      book_.note(run_->id(), EventKind::kNotHalted, Outcome::kNone,
                 "out of service, but it cannot be interrupted now: it finishes");
  }
  if (started_) kick();
}

}  // namespace rondo::exec
