// The executor's delivery jobs (MISSION.md §5): a pickup and its drop stand or fall together, what
// is on board is planned with (capacity, look-alike objects), and an object is never left in the
// robot: a drop that did not happen gets a task that takes the object back.
#include <fmt/format.h>

#include <algorithm>

#include "deliveries.h"
#include "dispatcher.h"
#include "rondo/exec/executor.h"
#include "task_run.h"

namespace rondo::exec {
namespace {

constexpr std::size_t kMaxReturns = 3;  // tries to take an object back before it is left on board

}  // namespace

std::vector<OnBoard> Executor::on_board() const { return deliveries_->on_board(book_); }

std::vector<OnBoard> Executor::on_board_when_free() const {
  std::vector<OnBoard> items = on_board();
  // The running task, then the on-demand queue (an opportunity taken waits there): free_at() runs
  // them first.
  const auto after = [&items](const Task& t) {
    if (!t.delivery) return;
    const Delivery& d = *t.delivery;
    if (d.role == DeliveryRole::kPickup)
      items.push_back({.job = d.job, .object = d.object, .appearance = d.appearance, .load = d.load,
                       .picked_up_by = t.id});
    else
      std::erase_if(items, [&](const OnBoard& o) { return o.job == d.job; });
  };
  if (run_ && !run_->waiting()) after(run_->task());
  for (const TaskId& id : dispatcher_->on_demand()) after(book_.at(id).task);
  return items;
}

void Executor::cancel_job_of(const TaskId& id, const std::string& why) {
  const Task& t = book_.at(id).task;
  if (!t.delivery || deliveries_->is_on_board(book_, t.delivery->job)) return;
  const Deliveries::Job* job = deliveries_->job(t.delivery->job);
  if (job == nullptr) return;  // settled and forgotten
  std::vector<TaskId> others = job->drops;
  if (job->pickup) others.push_back(*job->pickup);
  for (const TaskId& other : others)
    if (other != id && !book_.finished(other))
      (void)cancel_task(other, fmt::format("with the rest of its delivery ({})", why));
}

std::vector<TaskId> Executor::settle_jobs() {
  std::vector<TaskId> returns;
  const std::vector<std::string> open(deliveries_->open().begin(), deliveries_->open().end());
  for (const std::string& name : open) {
    const Deliveries::Job& job = *deliveries_->job(name);
    const bool on = deliveries_->is_on_board(book_, name);
    const bool pickup_live = job.pickup && !book_.finished(*job.pickup);
    std::vector<TaskId> pending;
    for (const TaskId& d : job.drops)
      if (!book_.finished(d)) pending.push_back(d);
    if (!on && !pickup_live) {  // delivered, or nothing to deliver any more
      const std::string why = job.pickup
                                  ? fmt::format("its pickup {} {}: nothing to deliver", *job.pickup,
                                                to_string(book_.state_of(*job.pickup).value_or(TaskState::kFailed)))
                                  : std::string("its job has no pickup and nothing of it is on board");
      for (const TaskId& d : pending) {
        if (run_ && run_->id() == d) continue;  // a drop that runs ends by itself
        if (run_ && run_->waiting() && run_->id() == d) end_wait();
        dispatcher_->forget(d);
        book_.at(d).planned_start.reset();
        book_.at(d).planned_end.reset();
        book_.transition(d, TaskState::kFailed, Outcome::kPickupFailed, why);
      }
      deliveries_->close(name);
      continue;
    }
    if (!on || !pending.empty()) continue;
    // On board, and no drop of it is pending: take it back (again, up to kMaxReturns times).
    // The last drop is final, so it may have left memory: read back from the store then.
    auto found = book_.lookup(job.drops.back(), zone_);
    if (!found || !*found) {
      book_.write_error(found ? fmt::format("delivery {}: its drop {} is gone", name, job.drops.back())
                              : found.error().message);
      deliveries_->close(name);
      continue;
    }
    const TaskRecord& last = **found;
    const Delivery& what = *last.task.delivery;
    if (job.drops.size() > kMaxReturns) {
      book_.note(last.task.id, EventKind::kStaysOnBoard, Outcome::kReturnPlanned,
                 fmt::format("the {} stays on board: {} returns ended without it", what.object, kMaxReturns));
      deliveries_->close(name);
      continue;
    }
    Task back;
    const TaskId& own = job.drops.front();
    back.id = own + "-return";
    for (int n = 2; book_.known(back.id); ++n) back.id = fmt::format("{}-return{}", own, n);
    back.start_node = options_.return_to.empty() ? job.pickup_place : options_.return_to;
    back.activity = fmt::format("take the {} back to {}", what.object, back.start_node);
    const Time now = clock_.now();
    back.window = TimeWindow{now, now + std::max(options_.return_within, last.task.duration)};
    back.duration = last.task.duration;
    back.priority = last.task.priority;
    back.actions = {Action{.name = "unload", .args = {{"object", what.object}}}};
    back.delivery = Delivery{.job = name, .role = DeliveryRole::kDrop, .object = what.object,
                             .appearance = what.appearance, .load = what.load};
    if (auto ok = book_.add({back}, "executor", nullptr, {options_.robot_name}); !ok) {
      book_.write_error(ok.error().message);
      deliveries_->close(name);
      continue;
    }
    deliveries_->add(back);
    book_.note(last.task.id, EventKind::kReturnPlanned, Outcome::kReturnPlanned,
               fmt::format("the {} is on board after this drop {}: task {} takes it back to {} by {}", what.object,
                           to_string(last.state), back.id, back.start_node,
                           zone_.format_clock(back.window->deadline)));
    returns.push_back(back.id);
  }
  return returns;
}

}  // namespace rondo::exec
