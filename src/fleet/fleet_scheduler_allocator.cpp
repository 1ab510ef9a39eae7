#include "rondo/fleet/fleet_scheduler_allocator.h"

#include <fmt/format.h>

#include <algorithm>
#include <string>

#include "rondo/schedule/fleet_scheduler.h"
#include "rondo/schedule/stop_condition.h"

namespace rondo::fleet {
namespace {

using Solved = std::pair<AllocationProblem, schedule::FleetPlan>;

// A delivery passes over a robot that cannot take its object on board now, when another may.
std::vector<AllocationUnit> with_room(const std::vector<AllocationUnit>& given,
                                      const std::vector<const exec::Executor*>& robots) {
  std::vector<AllocationUnit> units = given;
  for (AllocationUnit& unit : units) {
    std::vector<std::size_t> room;
    for (const std::size_t r : unit.eligible)
      if (room_on_board(unit, *robots[r])) room.push_back(r);
    if (!room.empty()) unit.eligible = std::move(room);
  }
  return units;
}

bool any_unit(const AllocationProblem& ap) {
  return std::any_of(ap.unit_tasks.begin(), ap.unit_tasks.end(), [](const auto& tasks) { return !tasks.empty(); });
}

// Each unit the plan holds, on an eligible robot: its allocation, with its place for the `why`.
void place_units(const std::vector<AllocationUnit>& units, const Solved& solved, const exec::Building& building,
                 bool inserted, std::vector<std::optional<Allocation>>& chosen) {
  const auto& [ap, plan] = solved;
  struct Place {
    std::size_t route = 0, position = 0;
    Time start{};
  };
  std::vector<std::optional<Place>> place_of(ap.problem.tasks.size());
  for (std::size_t r = 0; r < plan.routes.size(); ++r)
    for (std::size_t k = 0; k < plan.routes[r].size(); ++k)
      place_of[plan.routes[r][k].task] = Place{r, k, plan.routes[r][k].start};
  for (std::size_t u = 0; u < units.size(); ++u) {
    if (units[u].eligible.size() == 1 || ap.unit_tasks[u].empty()) continue;
    const std::optional<Place> at = place_of[ap.unit_tasks[u].front()];
    if (!at) continue;
    const std::size_t robot = ap.robots[at->route];
    // The plan honours the unit's robots (its action); kept as a guard all the same.
    if (std::find(units[u].eligible.begin(), units[u].eligible.end(), robot) == units[u].eligible.end()) continue;
    const std::string where = fmt::format("{} of {} on its route, at {}", at->position + 1,
                                          plan.routes[at->route].size(), building.zone.format_clock(at->start));
    chosen[u] = Allocation{.robot = robot,
                           .fits = true,
                           .why = inserted ? fmt::format("inserted into the plans of {} robots ({} tasks), it is {}",
                                                         ap.robots.size(), ap.problem.tasks.size(), where)
                                           : fmt::format("the fleet plan of {} tasks on {} robots puts it {}",
                                                         ap.problem.tasks.size(), ap.robots.size(), where)};
  }
}

// Every unit of the problem that the plan decides (more than one robot may take it) is in it.
bool holds_every_unit(const std::vector<AllocationUnit>& units, const Solved& solved) {
  const auto& [ap, plan] = solved;
  std::vector<bool> planned(ap.problem.tasks.size(), false);
  for (const auto& route : plan.routes)
    for (const schedule::ScheduledTask& e : route) planned[e.task] = true;
  for (std::size_t u = 0; u < units.size(); ++u)
    if (units[u].eligible.size() > 1)
      for (std::size_t t : ap.unit_tasks[u])
        if (!planned[t]) return false;
  return true;
}

}  // namespace

std::optional<Solved> FleetSchedulerAllocator::insert_units(const std::vector<AllocationUnit>& units,
                                                            const std::vector<const exec::Executor*>& robots,
                                                            const exec::Building& building) {
  const auto in_problem = [&](const AllocationUnit& u) { return in_allocation_problem(u, building.map); };
  const auto count = static_cast<std::size_t>(std::count_if(units.begin(), units.end(), in_problem));
  if (count == 0 || count > options_.insert_units) return std::nullopt;
  std::size_t planned = 0;
  Time now = Time::max();
  for (const exec::Executor* robot : robots) {
    planned += robot->activity().planned.size();
    now = std::min(now, robot->free_at().second);
  }
  if (planned < options_.insert_from_planned) return std::nullopt;
  Solved solved{allocation_problem(units, robots, building, options_.speed_factors, held_travel_.get(building, now)),
                {}};
  AllocationProblem& ap = solved.first;
  if (!any_unit(ap) || !schedule::validate_fleet(ap.problem)) return std::nullopt;
  std::vector<std::size_t> fresh;
  for (const auto& tasks : ap.unit_tasks) fresh.insert(fresh.end(), tasks.begin(), tasks.end());
  // A poll per repair round: the rounds bound it, the budget only keeps it finite.
  const schedule::PollBudgetStop budget(static_cast<std::int64_t>((fresh.size() + 1) * (options_.repair_rounds + 1)));
  solved.second = schedule::FleetScheduler({.seed = options_.seed, .repair_iterations = options_.repair_rounds})
                      .insert(ap.problem, ap.orders, fresh, budget);
  if (!holds_every_unit(units, solved)) {
    ++counts_.fell_back;
    return std::nullopt;
  }
  ++counts_.inserted;
  return solved;
}

std::optional<Solved> FleetSchedulerAllocator::solve_units(const std::vector<AllocationUnit>& units,
                                                           const std::vector<const exec::Executor*>& robots,
                                                           const exec::Building& building) const {
  AllocationProblem ap = allocation_problem(units, robots, building, options_.speed_factors);
  if (!any_unit(ap) || !schedule::validate_fleet(ap.problem)) return std::nullopt;
  const schedule::PollBudgetStop budget(static_cast<std::int64_t>(ap.problem.tasks.size()) + options_.search_polls);
  schedule::FleetPlan plan = schedule::FleetScheduler({.seed = options_.seed}).solve(ap.problem, budget);
  return Solved{std::move(ap), std::move(plan)};
}

std::vector<Allocation> FleetSchedulerAllocator::allocate(const std::vector<AllocationUnit>& given,
                                                          const std::vector<const exec::Executor*>& robots,
                                                          const exec::Building& building) {
  const std::vector<AllocationUnit> units = with_room(given, robots);
  std::vector<std::optional<Allocation>> chosen(units.size());
  const bool choices =
      std::any_of(units.begin(), units.end(), [](const AllocationUnit& u) { return u.eligible.size() > 1; });
  if (choices) {
    std::optional<Solved> solved = insert_units(units, robots, building);
    const bool inserted = solved.has_value();
    if (!inserted) {
      solved = solve_units(units, robots, building);
      if (solved) ++counts_.solved;
    }
    if (solved) {
      place_units(units, *solved, building, inserted, chosen);
      last_problem_ = std::move(solved->first);
      last_plan_ = std::move(solved->second);
    }
  }
  // On-demand and spec units, those eligible on one robot, and those the plan left out: the greedy's.
  if (std::any_of(chosen.begin(), chosen.end(), [](const auto& c) { return !c; })) {
    const std::vector<Allocation> greedy = GreedyAllocator().allocate(units, robots, building);
    for (std::size_t u = 0; u < units.size(); ++u)
      if (!chosen[u]) chosen[u] = greedy[u];
  }
  std::vector<Allocation> out;
  out.reserve(units.size());
  for (auto& c : chosen) out.push_back(std::move(*c));
  return out;
}

}  // namespace rondo::fleet
