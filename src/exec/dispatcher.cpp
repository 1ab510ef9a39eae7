#include "dispatcher.h"

#include <fmt/format.h>

#include <algorithm>

#include "text.h"

namespace rondo::exec {

Decision Dispatcher::next(map::NodeIndex here, Time now) {
  if (!on_demand.empty()) {  // on-demand tasks go first, in the order they came
    Decision d{.kind = Decision::Kind::kRun, .task = on_demand.front()};
    on_demand.pop_front();
    return d;
  }
  if (planned.empty()) return {.kind = here == options_.dock ? Decision::Kind::kStay : Decision::Kind::kDock};
  const TaskId id = planned.front();
  const TaskRecord& r = book_.at(id);
  const Task& task = r.task;
  const Duration travel = travel_.travel(here, *map_.find_node(task.start_node), now);
  const Time latest_start = task.window->deadline - r.remaining();
  if (travel >= kUnreachable || now + travel > latest_start) {
    planned.erase(planned.begin());
    const std::string& from = map_.node(here).name;
    if (travel >= kUnreachable)
      return {.kind = Decision::Kind::kFail, .task = id, .outcome = Outcome::kNoRoute,
              .reason = fmt::format("too late: {} cannot be reached from {} at {}", task.start_node, from,
                                    zone_.format_clock(now))};
    return {.kind = Decision::Kind::kFail, .task = id, .outcome = Outcome::kTooLate,
            .reason = fmt::format("too late: leaving {} at {} arrives at {} about {} (travel {}), after the latest "
                                  "start {} that finishes by {}",
                                  from, zone_.format_clock(now), task.start_node, zone_.format_clock(now + travel),
                                  duration_text(travel), zone_.format_clock(latest_start),
                                  zone_.format_clock(task.window->deadline))};
  }
  Time depart = r.release() - travel;
  // Held back for a blocked way: the travel now counts that way's failures, so leave by the travel
  // expected at the retry time instead.
  if (r.not_before && *r.not_before > now)
    depart = std::max(depart, *r.not_before - travel_.travel(here, *map_.find_node(task.start_node), *r.not_before));
  if (now < depart && depart - now > options_.dock_when_waiting_over) {  // a long wait: on the charger
    if (here != options_.dock) return {.kind = Decision::Kind::kDock};
    return {.kind = Decision::Kind::kIdleUntil, .until = depart};
  }
  planned.erase(planned.begin());
  if (now < depart) return {.kind = Decision::Kind::kWait, .task = id, .until = depart};
  return {.kind = Decision::Kind::kRun, .task = id};
}

void Dispatcher::forget(const TaskId& id) {
  std::erase(planned, id);
  std::erase(deferred, id);
  std::erase(on_demand, id);
}

}  // namespace rondo::exec
