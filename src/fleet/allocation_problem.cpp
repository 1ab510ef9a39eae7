#include "rondo/fleet/allocation_problem.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <set>
#include <unordered_map>

namespace rondo::fleet {
namespace {

bool on_demand(const AllocationUnit& unit) {
  return std::any_of(unit.tasks.begin(), unit.tasks.end(),
                     [](const Task* t) { return t->kind == TaskKind::kOnDemand; });
}

// Where a task starts and ends on the map.
struct Places {
  map::NodeIndex start = 0, end = 0;
};

// A task the solver can place: a window that still leaves room for its work, and a start node
// (and its end node, when it names one); its places.
std::optional<Places> plannable(const Task& t, Time release, Duration work, const map::TopoMap& map) {
  if (!t.window || t.has_spec() || release + work > t.window->deadline) return std::nullopt;
  const std::optional<map::NodeIndex> start = map.find_node(t.start_node);
  if (!start) return std::nullopt;
  if (t.end_node.empty()) return Places{*start, *start};
  const std::optional<map::NodeIndex> end = map.find_node(t.end_node);
  if (!end) return std::nullopt;
  return Places{*start, *end};
}

// The problem as it is built: the map's nodes as locations, and the tasks' ids.
class Builder {
 public:
  // `every_node`: each map node is its own location (an oracle over the whole map).
  Builder(const exec::Building& building, schedule::FleetProblem& problem, bool every_node)
      : building_(building), problem_(problem), every_node_(every_node) {}

  schedule::LocationIndex location(map::NodeIndex n) {
    if (every_node_) return n;
    auto [it, fresh] = location_.emplace(n, nodes_.size());
    if (fresh) nodes_.push_back(n);
    return it->second;
  }

  // Adds a task (its `after` links within the problem are joined by link_after()).
  std::size_t add(const Task& t, Time release, Duration work, const Places& places) {
    const schedule::LocationIndex start = location(places.start);
    schedule::FleetTask f;
    f.task = {.id = t.id,
              .release = release,
              .deadline = t.window->deadline,
              .duration = work,
              .priority = t.priority,
              .start_location = start,
              .end_location = location(places.end)};
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
  bool every_node_;
  std::vector<map::NodeIndex> nodes_;
  std::map<map::NodeIndex, schedule::LocationIndex> location_;
  std::unordered_map<TaskId, std::size_t> index_;
  std::vector<const Task*> sources_;
};

}  // namespace

bool in_allocation_problem(const AllocationUnit& unit, const map::TopoMap& map) {
  if (on_demand(unit)) return false;
  return std::all_of(unit.tasks.begin(), unit.tasks.end(), [&](const Task* t) {
    return plannable(*t, t->window ? t->window->release : Time{}, t->duration, map).has_value();
  });
}

AllocationProblem allocation_problem(const std::vector<AllocationUnit>& units,
                                     const std::vector<const exec::Executor*>& robots, const exec::Building& building,
                                     const std::map<std::string, double>& speed_factors,
                                     std::shared_ptr<const exec::SchedulerTravel> travel) {
  AllocationProblem out;
  out.unit_tasks.resize(units.size());
  const auto in_problem = [&](const AllocationUnit& unit) { return in_allocation_problem(unit, building.map); };
  std::set<std::size_t> involved;
  for (const AllocationUnit& unit : units)
    if (in_problem(unit)) involved.insert(unit.eligible.begin(), unit.eligible.end());
  out.robots.assign(involved.begin(), involved.end());
  std::map<std::size_t, std::size_t> robot_index;  // fleet index -> problem index
  for (std::size_t i = 0; i < out.robots.size(); ++i) robot_index[out.robots[i]] = i;

  schedule::FleetProblem& p = out.problem;
  Builder build(building, p, travel != nullptr);
  out.orders.resize(out.robots.size());
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
      if (!r) continue;
      const std::optional<Places> places = plannable(r->task, r->release(), r->remaining(), building.map);
      if (!places) continue;
      const std::size_t k = build.add(r->task, r->release(), r->remaining(), *places);
      p.tasks[k].pinned_robot = i;
      out.orders[i].push_back(k);
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
      const std::size_t k =
          build.add(*t, t->window->release, t->duration, *plannable(*t, t->window->release, t->duration, building.map));
      p.tasks[k].pinned_robot = pin;
      p.tasks[k].action = action;
      out.unit_tasks[u].push_back(k);
    }
  }
  build.pair_deliveries();
  build.link_after();
  if (travel) {
    p.travel = std::move(travel);
  } else {
    p.travel = std::make_shared<exec::SchedulerTravel>(building.travel, build.nodes());
  }
  return out;
}

}  // namespace rondo::fleet
