// A robot's part of a restart (fleet::Fleet::restore() does the building's): its tasks back in its
// queues as the store left them.
#include "deliveries.h"
#include "dispatcher.h"
#include "rondo/exec/executor.h"

namespace rondo::exec {

void Executor::restored(const TaskRecord& record) {
  deliveries_->add(record.task);
}

void Executor::restore_task(const TaskId& id) {
  const TaskRecord& r = book_.at(id);
  const Time now = clock_.now();
  if (r.task.kind == TaskKind::kOnDemand) {
    dispatcher_->queue_on_demand(id);
    if (r.not_before && *r.not_before > now) clock_.schedule_at(*r.not_before, [this] { on_demand_due(); });
  } else if (r.door_wait && r.task.window) {
    // Blocked by a door seen closed: it waits for the door again, with its retry and its end.
    const DoorWait wait = *r.door_wait;
    wait_for_door(id, wait);
  } else if (r.dropped_for_now && r.task.window) {
    // Offered again at every reschedule, and dropped for good once its window cannot be met.
    dispatcher_->defer(id);
    clock_.schedule_at(r.task.window->deadline - r.remaining() + milliseconds(1), [this] { (void)reoffer_deferred(); });
  }
  // A queued standard task: schedule_restored() schedules it.
}

}  // namespace rondo::exec
