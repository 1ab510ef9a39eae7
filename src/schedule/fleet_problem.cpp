#include "rondo/schedule/fleet_problem.h"

#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

namespace rondo::schedule {

double FleetProblem::distance_between(LocationIndex from, LocationIndex to) const {
  if (!distance.empty()) return distance[from * travel->location_count() + to];
  return to_seconds(travel->lower_bound(from, to));
}

Duration robot_travel(const FleetProblem& p, std::size_t robot, LocationIndex from, LocationIndex to, Time depart) {
  const Duration d = p.travel_of(robot).travel(from, to, depart);
  const double speed = p.robots[robot].speed_factor;
  if (speed == 1.0) return d;
  return Duration{static_cast<std::int64_t>(std::ceil(static_cast<double>(d.count()) / speed))};
}

namespace {

Status validate_robots(const FleetProblem& p, std::size_t locations) {
  for (std::size_t r = 0; r < p.robots.size(); ++r) {
    const FleetRobot& robot = p.robots[r];
    const std::string name = robot.name.empty() ? fmt::format("robots[{}]", r) : robot.name;
    if (!robot.travel && !p.travel) return Error::invalid(fmt::format("robot '{}': no travel oracle", name));
    const std::size_t own = p.travel_of(r).location_count();
    if (robot.location >= own) return Error::invalid(fmt::format("robot '{}': location {} out of range", name, robot.location));
    if (robot.end && robot.end->location >= own)
      return Error::invalid(fmt::format("robot '{}': dock location {} out of range", name, robot.end->location));
    if (!(robot.speed_factor > 0) || !std::isfinite(robot.speed_factor))
      return Error::invalid(fmt::format("robot '{}': speed factor must be above 0", name));
    if (robot.capacity < 0) return Error::invalid(fmt::format("robot '{}': negative capacity", name));
    if (own != locations)
      return Error::invalid(fmt::format("robot '{}': its travel has {} locations, the problem {}", name, own, locations));
  }
  return {};
}

Status validate_tasks(const FleetProblem& p, std::size_t locations) {
  std::map<std::string, int> pickups, drops;
  for (std::size_t i = 0; i < p.tasks.size(); ++i) {
    const FleetTask& f = p.tasks[i];
    const ProblemTask& t = f.task;
    const std::string where = fmt::format("task '{}'", t.id);
    if (t.start_location >= locations || t.end_location >= locations)
      return Error::invalid(where + ": location out of range");
    if (t.duration < Duration{0}) return Error::invalid(where + ": negative duration");
    if (f.demand < 0) return Error::invalid(where + ": negative demand");
    if (t.release > t.latest_start()) return Error::invalid(where + ": empty window");
    if (f.pinned_robot && *f.pinned_robot >= p.robots.size()) return Error::invalid(where + ": pinned robot out of range");
    for (std::size_t a : t.after)
      if (a >= p.tasks.size() || a == i) return Error::invalid(where + ": `after` index out of range");
    if (t.transfer) {
      auto& count = t.transfer->action == ItemAction::kPickup ? pickups[t.transfer->job] : drops[t.transfer->job];
      if (++count > 1) return Error::invalid(where + fmt::format(": job '{}' appears twice", t.transfer->job));
    }
  }
  for (const auto& [job, n] : drops)
    if (!pickups.count(job)) return Error::invalid(fmt::format("job '{}': a drop without its pickup", job));
  for (const auto& [job, n] : pickups)
    if (!drops.count(job)) return Error::invalid(fmt::format("job '{}': a pickup without its drop", job));
  // `after` acyclic: depth-first search with colours.
  std::vector<int> colour(p.tasks.size(), 0);
  auto visit = [&](auto&& self, std::size_t i) -> bool {
    colour[i] = 1;
    for (std::size_t a : p.tasks[i].task.after) {
      if (colour[a] == 1) return false;
      if (colour[a] == 0 && !self(self, a)) return false;
    }
    colour[i] = 2;
    return true;
  };
  for (std::size_t i = 0; i < p.tasks.size(); ++i)
    if (colour[i] == 0 && !visit(visit, i))
      return Error::invalid(fmt::format("task '{}': `after` links form a cycle", p.tasks[i].task.id));
  return {};
}

}  // namespace

Status validate_fleet(const FleetProblem& p) {
  if (!p.travel) return Error::invalid("a fleet problem needs a shared travel oracle (FleetProblem::travel)");
  if (p.robots.empty()) return Error::invalid("a fleet problem needs at least one robot");
  const std::size_t locations = p.travel->location_count();
  if (!p.distance.empty() && p.distance.size() != locations * locations)
    return Error::invalid(fmt::format("distance: {} entries for {} locations", p.distance.size(), locations));
  RONDO_RETURN_IF_ERROR(validate_robots(p, locations));
  return validate_tasks(p, locations);
}

}  // namespace rondo::schedule
