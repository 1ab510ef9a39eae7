// The service's additions to the executor (`rondo serve`, rondo::service): a read-only view of
// what it is doing, and the changes a person makes while it runs (a waiting task's window or
// priority, out of service). Everything here runs on the clock's thread, like the
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
  if (unable_) unable_();
}

}  // namespace rondo::exec
