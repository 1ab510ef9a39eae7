#include "rondo/fleet/fleet_scheduler_allocator.h"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <set>

#include "rondo/exec/map_travel.h"
#include "rondo/schedule/fleet_scheduler.h"
#include "rondo/schedule/stop_condition.h"

namespace rondo::fleet {
namespace {

bool on_demand(const AllocationUnit& unit) {
  return std::any_of(unit.tasks.begin(), unit.tasks.end(),
                     [](const Task* t) { return t->kind == TaskKind::kOnDemand; });
}

// A task the solver can place: a window that still leaves room for its work, and a start node.
bool plannable(const Task& t, Time release, Duration work, const map::TopoMap& map) {
  return t.window && !t.has_spec() && map.find_node(t.start_node) &&
         (t.end_node.empty() || map.find_node(t.end_node)) && release + work <= t.window->deadline;
}

// The problem as it is built: the map's nodes as locations, and the tasks' ids.
class Builder {
 public:
  Builder(const exec::Building& building, schedule::FleetProblem& problem) : building_(building), problem_(problem) {}

  schedule::LocationIndex location(map::NodeIndex n) {
    auto [it, fresh] = location_.emplace(n, nodes_.size());
    if (fresh) nodes_.push_back(n);
    return it->second;
  }

  // Adds a task (its `after` links within the problem are joined by link_after()).
  std::size_t add(const Task& t, Time release, Duration work) {
    const schedule::LocationIndex start = location(*building_.map.find_node(t.start_node));
    schedule::FleetTask f;
    f.task = {.id = t.id,
              .release = release,
              .deadline = t.window->deadline,
              .duration = work,
              .priority = t.priority,
              .start_location = start,
              .end_location = t.end_node.empty() ? start : location(*building_.map.find_node(t.end_node))};
    problem_.tasks.push_back(std::move(f));
    index_.emplace(t.id, problem_.tasks.size() - 1);
    sources_.push_back(&t);
    return problem_.tasks.size() - 1;
  }

  // A delivery half becomes a transfer only with its partner in the problem on the same robot:
  // a drop whose object is on board already (its pickup done) is a plain task.
  void pair_deliveries() {
    std::map<std::string, std::vector<std::size_t>> halves;  // job -> its tasks here
    for (std::size_t i = 0; i < sources_.size(); ++i)
      if (sources_[i]->delivery) halves[sources_[i]->delivery->job].push_back(i);
    for (const auto& [job, tasks] : halves) {
      if (tasks.size() != 2) continue;
      const Delivery& a = *sources_[tasks[0]]->delivery;
      const Delivery& b = *sources_[tasks[1]]->delivery;
      if (a.role == b.role || problem_.tasks[tasks[0]].pinned_robot != problem_.tasks[tasks[1]].pinned_robot) continue;
      for (std::size_t i : tasks) {
        const Delivery& d = *sources_[i]->delivery;
        problem_.tasks[i].task.transfer = schedule::ItemTransfer{
            .job = d.job,
            .action = d.role == DeliveryRole::kPickup ? schedule::ItemAction::kPickup : schedule::ItemAction::kDrop,
            .appearance = d.appearance,
            .load = d.load};
      }
    }
  }

  // `after` links between tasks of the problem on the same robot (or both unpinned: one unit).
  void link_after() {
    for (std::size_t i = 0; i < sources_.size(); ++i)
      for (const TaskId& a : sources_[i]->after)
        if (auto it = index_.find(a); it != index_.end() && it->second != i &&
                                      problem_.tasks[it->second].pinned_robot == problem_.tasks[i].pinned_robot)
          problem_.tasks[i].task.after.push_back(it->second);
  }

  const std::vector<map::NodeIndex>& nodes() const { return nodes_; }

 private:
  const exec::Building& building_;
  schedule::FleetProblem& problem_;
  std::vector<map::NodeIndex> nodes_;
  std::map<map::NodeIndex, schedule::LocationIndex> location_;
  std::map<TaskId, std::size_t> index_;
  std::vector<const Task*> sources_;
};

}  // namespace

AllocationProblem allocation_problem(const std::vector<AllocationUnit>& units,
                                     const std::vector<const exec::Executor*>& robots, const exec::Building& building,
                                     const std::map<std::string, double>& speed_factors) {
  AllocationProblem out;
  out.unit_tasks.resize(units.size());
  const auto in_problem = [&](const AllocationUnit& unit) {
    if (on_demand(unit)) return false;
    return std::all_of(unit.tasks.begin(), unit.tasks.end(), [&](const Task* t) {
      return plannable(*t, t->window ? t->window->release : Time{}, t->duration, building.map);
    });
  };
  std::set<std::size_t> involved;
  for (const AllocationUnit& unit : units)
    if (in_problem(unit)) involved.insert(unit.eligible.begin(), unit.eligible.end());
  out.robots.assign(involved.begin(), involved.end());
  std::map<std::size_t, std::size_t> robot_index;  // fleet index -> problem index
  for (std::size_t i = 0; i < out.robots.size(); ++i) robot_index[out.robots[i]] = i;

  schedule::FleetProblem& p = out.problem;
  Builder build(building, p);
  for (std::size_t i = 0; i < out.robots.size(); ++i) {
    const exec::Executor& robot = *robots[out.robots[i]];
    const auto [at, free] = robot.free_at();
    // Its pace as learned from the fleet's traversals (Building::speeds), else as declared.
    const auto declared = speed_factors.find(robot.name());
    const auto learned = building.speeds.factors().find(robot.name());
    const double speed = learned != building.speeds.factors().end() ? learned->second
                         : declared != speed_factors.end()          ? declared->second
                                                                    : 1.0;
    p.robots.push_back({.name = robot.name(),
                        .location = build.location(at),
                        .free_from = free,
                        .end = std::nullopt,
                        .actions = {},
                        .capacity = robot.capacity(),
                        .speed_factor = speed,
                        .travel = nullptr});
    // What it has planned stays on it.
    for (const TaskId& id : robot.activity().planned) {
      const exec::TaskRecord* r = building.book.find(id);
      if (!r || !plannable(r->task, r->release(), r->remaining(), building.map)) continue;
      const std::size_t k = build.add(r->task, r->release(), r->remaining());
      p.tasks[k].pinned_robot = i;
    }
  }
  out.planned_tasks = p.tasks.size();

  // A unit eligible on some of the problem's robots only: an action that only those list.
  std::map<std::vector<std::size_t>, std::string> action_of;  // eligible robots -> its action
  for (std::size_t u = 0; u < units.size(); ++u) {
    const AllocationUnit& unit = units[u];
    if (!in_problem(unit)) continue;
    std::optional<std::size_t> pin;
    std::string action;
    if (unit.eligible.size() == 1) {
      pin = robot_index.at(unit.eligible.front());
    } else if (unit.eligible.size() < out.robots.size()) {
      std::vector<std::size_t> may = unit.eligible;
      std::sort(may.begin(), may.end());
      auto [it, fresh] = action_of.emplace(may, fmt::format("eligible-{}", action_of.size()));
      if (fresh)
        for (std::size_t r : may) p.robots[robot_index.at(r)].actions.push_back(it->second);
      action = it->second;
    }
    for (const Task* t : unit.tasks) {
      const std::size_t k = build.add(*t, t->window->release, t->duration);
      p.tasks[k].pinned_robot = pin;
      p.tasks[k].action = action;
      out.unit_tasks[u].push_back(k);
    }
  }
  build.pair_deliveries();
  build.link_after();
  p.travel = std::make_shared<exec::SchedulerTravel>(building.travel, build.nodes());
  return out;
}

std::vector<Allocation> FleetSchedulerAllocator::allocate(const std::vector<AllocationUnit>& given,
                                                          const std::vector<const exec::Executor*>& robots,
                                                          const exec::Building& building) {
  // A delivery passes over a robot that cannot take its object on board now, when another may.
  std::vector<AllocationUnit> units = given;
  for (AllocationUnit& unit : units) {
    std::vector<std::size_t> room;
    for (const std::size_t r : unit.eligible)
      if (room_on_board(unit, *robots[r])) room.push_back(r);
    if (!room.empty()) unit.eligible = std::move(room);
  }
  std::vector<std::optional<Allocation>> chosen(units.size());
  const bool choices =
      std::any_of(units.begin(), units.end(), [](const AllocationUnit& u) { return u.eligible.size() > 1; });
  if (choices) {
    AllocationProblem ap = allocation_problem(units, robots, building, options_.speed_factors);
    const bool any =
        std::any_of(ap.unit_tasks.begin(), ap.unit_tasks.end(), [&](const auto& tasks) { return !tasks.empty(); });
    if (any && schedule::validate_fleet(ap.problem)) {
      const schedule::PollBudgetStop budget(static_cast<std::int64_t>(ap.problem.tasks.size()) + options_.search_polls);
      schedule::FleetPlan plan = schedule::FleetScheduler({.seed = options_.seed}).solve(ap.problem, budget);
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
        chosen[u] = Allocation{
            .robot = robot,
            .fits = true,
            .why = fmt::format("the fleet plan of {} tasks on {} robots puts it {} of {} on its route, at {}",
                               ap.problem.tasks.size(), ap.robots.size(), at->position + 1,
                               plan.routes[at->route].size(), building.zone.format_clock(at->start))};
      }
      last_problem_ = std::move(ap);
      last_plan_ = std::move(plan);
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
