// The executor's part in the building's traffic (docs/traffic.md): parked or not for the
// reservations, moving aside when asked, and its stops published for the others to plan around.
#include <fmt/format.h>

#include <utility>
#include <vector>

#include "dispatcher.h"
#include "rondo/exec/executor.h"
#include "rondo/traffic/bookings.h"
#include "task_run.h"
#include "traffic_link.h"

namespace rondo::exec {

void Executor::update_parked() {
  if (traffic_) traffic_->set_parked(!in_fault_ && !robot_.busy() && !trip_ && (!run_ || run_->waiting()));
}

void Executor::make_way(const traffic::MakeWay& m) {
  if (in_fault_ || robot_.busy() || trip_ || (run_ && !run_->waiting())) return traffic_->decline(m);
  const std::string for_robots = traffic_->names(m.for_robots);
  if (run_) {
    const TaskId id = run_->id();
    end_wait();
    book_.transition(id, TaskState::kQueued, Outcome::kScheduleChanged,
                     fmt::format("waiting interrupted: making way for {}", for_robots));
    dispatcher_->put_first_in_plan(id);
  }
  const map::NodeIndex to = map_.to_index(m.route.back());
  book_.note_robot(options_.robot_name, EventKind::kMadeWay, Outcome::kNone,
                   fmt::format("to {} (parked), making way for {}", map_.node(to).name, for_robots));
  start_trip(JourneyPurpose::kMakeWay, to);
}

// Where it plans to stop: the running task's place from when it is expected there until its
// actions are expected done (committed: it has set out), and each planned task's place over the
// schedule's time for it. A spec task's place is not known before its journey ends: none.
void Executor::publish_stops() {
  if (!booking_) return;
  std::vector<traffic::Booking> stops;
  const auto place = [this](const TaskRecord& r) -> std::optional<map::NodeIndex> {
    if (r.task.has_spec() || r.task.start_node.empty() || r.actions_done >= r.action_count()) return std::nullopt;
    return map_.find_node(r.task.start_node);
  };
  const Time now = clock_.now();
  // The running task's stop is reckoned once, when it sets out (the others are told of it).
  if (!run_ || run_->waiting() || (committed_ && committed_->first != run_->id())) committed_.reset();
  if (run_ && !run_->waiting() && !committed_) {
    const TaskRecord& r = book_.at(run_->id());
    if (const std::optional<map::NodeIndex> n = place(r)) {
      const Duration travel = travel_.travel(robot_.location(), *n, now);
      if (travel < kUnreachable)
        committed_ = {r.task.id,
                      {.node = *n, .from = now + travel, .to = now + travel + r.remaining(), .committed = true}};
    }
  }
  if (committed_) stops.push_back(committed_->second);
  const auto planned = [&](const TaskId& id) {
    const TaskRecord& r = book_.at(id);
    if (!r.planned_start || !r.planned_end || *r.planned_end <= now) return;
    if (const std::optional<map::NodeIndex> n = place(r))
      stops.push_back({.node = *n, .from = *r.planned_start, .to = *r.planned_end});
  };
  if (run_ && run_->waiting()) planned(run_->id());
  for (const TaskId& id : dispatcher_->planned()) planned(id);
  building_.bookings->publish(*booking_, std::move(stops));
}

// Told from inside another robot's publish: looked at once that call is over. A robot waiting to
// set out for a task at such a node decides its departure again (it may have to wait longer, or
// may go sooner).
void Executor::stops_changed(map::NodeIndex node) {
  stops_changed_at_.push_back(node);
  if (stops_look_ != 0) return;
  stops_look_ = clock_.schedule_after(Duration{0}, [this] {
    stops_look_ = 0;
    const std::vector<map::NodeIndex> nodes = std::exchange(stops_changed_at_, {});
    if (!run_ || !run_->waiting()) return;
    const Task& t = run_->task();
    if (t.has_spec() || t.start_node.empty()) return;
    const map::NodeIndex at = *map_.find_node(t.start_node);
    if (std::find(nodes.begin(), nodes.end(), at) == nodes.end()) return;
    requeue_waiting(Outcome::kScheduleChanged,
                    fmt::format("waiting interrupted: another robot's stop at {} came or went", t.start_node));
  });
}

}  // namespace rondo::exec
