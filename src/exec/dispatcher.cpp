#include "dispatcher.h"

#include <fmt/format.h>

#include <algorithm>

#include "spec_tasks.h"
#include "text.h"

namespace rondo::exec {

std::optional<TaskId> Dispatcher::ready_on_demand(Time now) const {
  for (const TaskId& id : on_demand_) {
    const TaskRecord& r = book_.at(id);
    if (!r.not_before || *r.not_before <= now) return id;
  }
  return std::nullopt;
}

Decision Dispatcher::next(map::NodeIndex here, Time now) {
  // On-demand tasks go first, in the order they came, but for one held back for a blocked way
  // until its retry time (the executor looks again then).
  if (const std::optional<TaskId> id = ready_on_demand(now)) {
    std::erase(on_demand_, *id);
    return {.kind = Decision::Kind::kRun, .task = *id};
  }
  if (const std::optional<PlannedCharge> c = charge_due(now))
    return {.kind = Decision::Kind::kCharge, .until = c->end, .level = c->target, .length = c->end - c->start};
  if (planned_.empty()) return {.kind = here == options_.dock ? Decision::Kind::kStay : Decision::Kind::kDock};
  const TaskId id = planned_.front();
  const TaskRecord& r = book_.at(id);
  const Task& task = r.task;
  const Duration travel = task_travel(travel_, specs_, map_, r, here, now);
  const std::string place = task.has_spec() ? "the way that satisfies " + task.spec : task.start_node;
  const Time latest_start = task.window->deadline - r.remaining();
  if (travel >= kUnreachable || now + travel > latest_start) {
    planned_.erase(planned_.begin());
    const std::string& from = map_.node(here).name;
    if (travel >= kUnreachable)
      return {
          .kind = Decision::Kind::kFail,
          .task = id,
          .outcome = Outcome::kNoRoute,
          .reason = fmt::format("too late: {} cannot be reached from {} at {}", place, from, zone_.format_clock(now))};
    return {.kind = Decision::Kind::kFail,
            .task = id,
            .outcome = Outcome::kTooLate,
            .reason = fmt::format("too late: leaving {} at {} arrives at {} about {} (travel {}), after the latest "
                                  "start {} that finishes by {}",
                                  from, zone_.format_clock(now), place, zone_.format_clock(now + travel),
                                  duration_text(travel), zone_.format_clock(latest_start),
                                  zone_.format_clock(task.window->deadline))};
  }
  Time depart = r.release() - travel;
  // Held back for a blocked way: the robot does not set out before the retry time. The travel
  // estimated now still counts that way's failures, and leaving early by the travel expected
  // then would reach the way before it is likely open again.
  if (r.not_before && *r.not_before > now) depart = std::max(depart, *r.not_before);
  // Another robot's stop there: set out so as to arrive when it has left, while the task can still
  // start in time (else go: the reservations make it wait its turn).
  Duration delay{0};
  std::string behind;
  if (const std::optional<PutOff> p = put_off(r, now, depart, travel)) {
    delay = p->depart - std::max(now, depart);
    depart = p->depart;
    behind = p->behind;
  }
  if (now < depart && depart - now > options_.dock_when_waiting_over) {  // a long wait: on the charger
    if (here != options_.dock) return {.kind = Decision::Kind::kDock};
    return {.kind = Decision::Kind::kIdleUntil, .until = depart};
  }
  planned_.erase(planned_.begin());
  if (now < depart)
    return {.kind = Decision::Kind::kWait, .task = id, .until = depart, .reason = behind, .traffic_delay = delay};
  return {.kind = Decision::Kind::kRun, .task = id};
}

std::optional<PutOff> Dispatcher::put_off(const TaskRecord& r, Time now, Time depart, Duration travel) const {
  const Task& task = r.task;
  if (!bookings_ || task.has_spec() || task.start_node.empty() || !task.window) return std::nullopt;
  const map::NodeIndex node = *map_.find_node(task.start_node);
  const Time leave = std::max(now, depart);
  const Time arrive = leave + travel;
  const Time free = bookings_->earliest(me_, node, arrive, r.remaining());
  if (free <= arrive || free > task.window->deadline - r.remaining()) return std::nullopt;
  const std::optional<traffic::Stop> stop = bookings_->behind(me_, node, arrive, r.remaining());
  return PutOff{
      .depart = leave + (free - arrive),
      .behind = fmt::format("{} stops at {} until about {}", stop ? bookings_->name(stop->robot) : "another robot",
                            task.start_node, zone_.format_clock(free))};
}

std::optional<PutOff> Dispatcher::put_off_now(const TaskId& id, map::NodeIndex here, Time now) const {
  const TaskRecord& r = book_.at(id);
  const Duration travel = task_travel(travel_, specs_, map_, r, here, now);
  if (travel >= kUnreachable) return std::nullopt;
  return put_off(r, now, now, travel);
}

std::optional<PlannedCharge> Dispatcher::charge_due(Time now) {
  while (!charges_.empty()) {
    const PlannedCharge c = charges_.front();
    bool due = planned_.empty() || (c.before && planned_.front() == *c.before);
    if (!due && !(c.before && is_planned(*c.before))) {
      // The task it was planned before has gone: by time.
      const TaskRecord& r = book_.at(planned_.front());
      due = !r.planned_start || *r.planned_start >= c.start;
    }
    if (!due) return std::nullopt;
    charges_.erase(charges_.begin());
    if (c.end > now) return c;  // else: its time has passed
  }
  return std::nullopt;
}

bool Dispatcher::is_planned(const TaskId& id) const {
  return std::find(planned_.begin(), planned_.end(), id) != planned_.end();
}

bool Dispatcher::is_deferred(const TaskId& id) const {
  return std::find(deferred_.begin(), deferred_.end(), id) != deferred_.end();
}

void Dispatcher::follow_schedule(std::vector<TaskId> order) {
  planned_ = std::move(order);
}

void Dispatcher::put_first_in_plan(const TaskId& id) {
  if (!is_planned(id)) planned_.insert(planned_.begin(), id);
}

void Dispatcher::put_first_on_demand(const TaskId& id) {
  std::erase(on_demand_, id);
  on_demand_.push_front(id);
}

void Dispatcher::defer(const TaskId& id) {
  if (!is_deferred(id)) deferred_.push_back(id);
}

void Dispatcher::forget(const TaskId& id) {
  std::erase(planned_, id);
  std::erase(deferred_, id);
  std::erase(on_demand_, id);
}

}  // namespace rondo::exec
