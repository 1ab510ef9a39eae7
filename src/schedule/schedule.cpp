#include "rondo/schedule/schedule.h"

#include <fmt/format.h>

namespace rondo::schedule {

std::string_view to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::kOptimal: return "optimal";
    case SolveStatus::kFeasible: return "feasible";
    case SolveStatus::kInfeasible: return "infeasible";
    case SolveStatus::kTimeout: return "timeout";
  }
  return "unknown";
}

std::vector<std::size_t> Schedule::order() const {
  std::vector<std::size_t> o;
  o.reserve(entries.size());
  for (const auto& e : entries) o.push_back(e.task);
  return o;
}

std::optional<double> Schedule::gap() const {
  if (!lower_bound || entries.empty()) return std::nullopt;
  const double obj = static_cast<double>(objective.count());
  if (obj <= 0) return 0.0;
  return std::max(0.0, (obj - static_cast<double>(lower_bound->count())) / obj);
}

Result<Schedule> time_order(const Problem& p, const std::vector<std::size_t>& order) {
  Schedule s;
  s.status = SolveStatus::kFeasible;
  Time now = p.robot.time;
  LocationIndex here = p.robot.location;
  for (std::size_t i : order) {
    if (i >= p.tasks.size()) return Error::invalid(fmt::format("order: task index {} out of range", i));
    const ProblemTask& t = p.tasks[i];
    ScheduledTask e;
    e.task = i;
    e.depart = now;
    e.travel = p.travel->travel(here, t.start_location, now);
    e.arrival = now + e.travel;
    e.start = std::max(e.arrival, t.release);
    e.waiting = e.start - e.arrival;
    e.end = e.start + t.duration;
    if (e.start > t.latest_start())
      return Error::invalid(fmt::format("task '{}' cannot start by {} (earliest {})", t.id,
                                        format_time(t.latest_start()), format_time(e.start)));
    if (p.window_travel && p.window_arrival(here, t.start_location, now) > t.latest_start())
      return Error::invalid(fmt::format("task '{}' starts by {} with too little chance (leaving at {})", t.id,
                                        format_time(t.latest_start()), format_time(now)));
    s.objective += e.end - p.robot.time;
    now = e.end;
    here = t.end_location;
    s.entries.push_back(e);
  }
  if (p.return_to) {
    const Time back = now + p.travel->travel(here, p.return_to->location, now);
    if (back > p.return_to->deadline)
      return Error::invalid(fmt::format("return to {} at {} is after its deadline {}",
                                        p.location_name(p.return_to->location), format_time(back),
                                        format_time(p.return_to->deadline)));
    s.return_arrival = back;
  }
  return s;
}

}  // namespace rondo::schedule
