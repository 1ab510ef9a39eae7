// Drops for now, fleet-wide (issue 38: "trySchedule and drop work fleet-wide"). A robot's scheduler
// drops for now what does not fit its own schedule; the fleet then offers each such task to the
// other robots, and moves it where the allocator finds it fits. A robot that finds itself free takes
// what fits it of the others' drops. A task is not offered back to a robot that dropped it within a
// slot (the travel estimates change by slot), so a task visits each robot at most once a slot and
// otherwise stays dropped for now on the last robot that tried it, which offers it again to its own
// scheduler as before. A task that names its robot stays; a delivery job moves whole (both halves
// dropped for now), and one begun on its robot stays there.
#include <fmt/format.h>

#include <map>

#include "rondo/fleet/fleet.h"

namespace rondo::fleet {
namespace {

// A task the fleet may move to another robot while it is dropped for now on `robot`.
bool movable(const exec::TaskRecord* r, const std::string& robot) {
  return r && r->state == TaskState::kQueued && r->dropped_for_now && r->robot == robot && r->task.robot.empty();
}

// Leaves out the halves of a delivery job whose other half is not among `tasks` (still planned, or
// running): a job moves whole or not at all. (A job begun on its robot never moves:
// Executor::release keeps it.)
void whole_jobs_only(std::vector<Task>& tasks, const exec::TaskBook& book) {
  std::map<std::string, int> open, offered;  // per job: halves not over, and halves among `tasks`
  for (const Task& t : tasks)
    if (t.delivery) offered[t.delivery->job]++;
  if (offered.empty()) return;
  for (const TaskId& id : book.order()) {
    const exec::TaskRecord& r = book.at(id);
    if (r.task.delivery && offered.contains(r.task.delivery->job) && !is_final(r.state)) open[r.task.delivery->job]++;
  }
  std::erase_if(tasks, [&](const Task& t) { return t.delivery && open[t.delivery->job] != offered[t.delivery->job]; });
}

}  // namespace

void Fleet::offer_dropped(exec::Executor& from, const std::vector<TaskId>& ids) {
  const Time now = building_.clock.now();
  std::erase_if(dropped_by_, [this](const auto& kv) {
    const exec::TaskRecord* r = building_.book.find(kv.first);
    return !r || is_final(r->state);
  });
  std::vector<Task> tasks;
  for (const TaskId& id : ids) {
    const exec::TaskRecord* r = building_.book.find(id);
    if (!movable(r, from.name())) continue;
    dropped_by_[id][from.name()] = now;
    tasks.push_back(r->task);
  }
  whole_jobs_only(tasks, building_.book);
  if (tasks.empty()) return;
  const Duration slot = options_.slot_width;
  move_if_fits(from, tasks, [this, now, slot](const Task& t, std::size_t robot) {
    const exec::Executor& r = *robots_[robot];
    if (!r.able() || r.paused()) return true;
    const auto by = dropped_by_.find(t.id);
    if (by == dropped_by_.end()) return false;
    const auto when = by->second.find(r.name());
    return when != by->second.end() && now - when->second < slot;
  });
}

void Fleet::offer_to_free(exec::Executor& robot) {
  if (!robot.able() || robot.paused()) return;
  const std::size_t me = index_of(robot.name());
  const Time now = building_.clock.now();
  const Duration slot = options_.slot_width;
  for (const auto& other : robots_) {
    if (other.get() == &robot) continue;
    std::vector<Task> tasks;
    for (const TaskId& id : other->deferred()) {
      const exec::TaskRecord* r = building_.book.find(id);
      if (!movable(r, other->name())) continue;
      if (const auto by = dropped_by_.find(id); by != dropped_by_.end()) {
        const auto when = by->second.find(robot.name());
        if (when != by->second.end() && now - when->second < slot) continue;
      }
      tasks.push_back(r->task);
    }
    whole_jobs_only(tasks, building_.book);
    if (!tasks.empty()) move_if_fits(*other, tasks, [me](const Task&, std::size_t r) { return r != me; });
  }
}

void Fleet::move_if_fits(exec::Executor& from, const std::vector<Task>& tasks, const Skip& skip) {
  const std::vector<Allocation> to = allocate(tasks, skip);
  std::vector<TaskId> moving;
  std::map<TaskId, std::string> why;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (to[i].robot >= robots_.size() || !to[i].fits || robots_[to[i].robot].get() == &from) continue;
    moving.push_back(tasks[i].id);
    why[tasks[i].id] =
        fmt::format("from {} (dropped for now there: {}) to {}: {}", from.name(),
                    building_.book.at(tasks[i].id).dropped_for_now->second, robots_[to[i].robot]->name(), to[i].why);
  }
  if (moving.empty()) return;
  const std::vector<TaskId> released = from.release(moving);
  for (const TaskId& id : released) {
    const std::size_t i = static_cast<std::size_t>(
        std::find_if(tasks.begin(), tasks.end(), [&](const Task& t) { return t.id == id; }) - tasks.begin());
    if (!building_.book.allocate(id, robots_[to[i].robot]->name())) continue;  // the store refused: it stays
    building_.book.note(id, exec::EventKind::kReallocated, exec::Outcome::kNone, why[id]);
  }
  hand_out(released);  // each to the robot the book now names
}

}  // namespace rondo::fleet
