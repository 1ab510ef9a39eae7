// Re-allocation: the unstarted tasks of a robot that cannot work go to the robots that can.
#include <fmt/format.h>

#include "rondo/fleet/fleet.h"

namespace rondo::fleet {

void Fleet::watch(exec::Executor& robot) {
  robot.on_unable([this, &robot] {
    if (robots_.size() < 2) return;
    building_.clock.schedule_after(robot.reallocate_after(), [this, &robot] { reallocate_from(robot); });
  });
}

void Fleet::offer_preempted(exec::Executor& robot, const TaskId& id) {
  const exec::TaskRecord* r = building_.book.find(id);
  if (!r || r->state != TaskState::kQueued || r->robot != robot.name()) return;  // moved on meanwhile
  const std::vector<Allocation> to = allocate({r->task});
  if (to[0].robot < robots_.size() && robots_[to[0].robot].get() != &robot) {
    const std::string& name = robots_[to[0].robot]->name();
    if (building_.book.allocate(id, name))
      building_.book.note(
          id, exec::EventKind::kReallocated, exec::Outcome::kPreemptedOnDemand,
          fmt::format("from {} (preempted by an on-demand task) to {}: {}", robot.name(), name, to[0].why));
  }
  hand_out({id});  // to the robot the book names: another, or back to its own
}

void Fleet::reallocate_from(exec::Executor& robot) {
  if (robot.able()) return;  // the fault cleared, or it is back in service: it keeps its work
  bool others = false;
  for (const auto& r : robots_) others = others || (r.get() != &robot && r->able());
  if (!others) return;
  // The running task too, when a fault holds it (out of service, the running task was halted or
  // finishes): it stops, keeps its progress, and follows once its run has ended.
  if (robot.paused()) robot.hand_back_running([this, &robot](const TaskId& id) { move_tasks(robot, {id}); });
  move_tasks(robot, robot.release());
}

void Fleet::move_tasks(exec::Executor& robot, const std::vector<TaskId>& ids) {
  if (ids.empty()) return;
  std::vector<Task> tasks;
  for (const TaskId& id : ids) tasks.push_back(building_.book.at(id).task);
  const std::vector<Allocation> to = allocate(tasks);
  const std::string why = robot.paused() ? "a fault" : "out of service";
  const Duration after = robot.reallocate_after();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (to[i].robot >= robots_.size()) continue;
    const std::string& name = robots_[to[i].robot]->name();
    if (name == robot.name()) continue;
    if (!building_.book.allocate(ids[i], name)) continue;  // the store refused: it goes back to its robot
    building_.book.note(ids[i], exec::EventKind::kReallocated,
                        robot.paused() ? exec::Outcome::kRobotFault : exec::Outcome::kNone,
                        fmt::format("from {} ({} for {}) to {}: {}", robot.name(), why,
                                    format_duration(std::chrono::round<std::chrono::seconds>(after)), name, to[i].why));
  }
  hand_out(ids);  // each to the robot the book now names
}

}  // namespace rondo::fleet
