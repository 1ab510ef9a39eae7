#include <algorithm>
#include <limits>
#include <map>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "rondo/fleet/allocator.h"

namespace rondo::fleet {
namespace {

// A task as a stop on a robot's way: where it starts and ends, how long it works, and its window.
struct Stop {
  map::NodeIndex start = 0;
  map::NodeIndex end = 0;
  Duration work{0};
  Time release{};
  Time latest{};
};

std::optional<Stop> stop_of(const Task& task, const exec::TaskRecord* record, const exec::Building& building) {
  const auto start = building.map.find_node(task.start_node);
  if (!start || !task.window) return std::nullopt;
  const auto end = task.end_node.empty() ? start : building.map.find_node(task.end_node);
  if (!end) return std::nullopt;
  const Duration work = record ? record->remaining() : task.duration;
  const Time release = record ? record->release() : task.window->release;
  return Stop{.start = *start, .end = *end, .work = work, .release = release, .latest = task.window->deadline - work};
}

// The expected travel of a robot's way from `from` at `t` through `stops`, or nothing when a stop
// would start after its latest start (or cannot be reached).
std::optional<Duration> way_travel(map::NodeIndex from, Time t, const std::vector<Stop>& stops,
                                   const exec::TravelCache& travel) {
  Duration total{0};
  map::NodeIndex at = from;
  for (const Stop& s : stops) {
    const Duration to = travel.travel(at, s.start, t);
    if (to >= exec::kUnreachable) return std::nullopt;
    const Time begin = std::max(t + to, s.release);
    if (begin > s.latest) return std::nullopt;
    t = begin + s.work;
    total += to;
    if (s.end != s.start) {
      const Duration on = travel.travel(s.start, s.end, t);
      if (on >= exec::kUnreachable) return std::nullopt;
      t += on;
      total += on;
    }
    at = s.end;
  }
  return total;
}

// A robot's way as the allocator builds it up: where it is next free, and its stops in order.
struct Way {
  map::NodeIndex from = 0;
  Time free{};
  std::vector<Stop> stops;
};

// Where `stop` fits `way` best after position `after`: the position and the way's travel then.
std::optional<std::pair<std::size_t, Duration>> best_insertion(const Way& way, const Stop& stop, std::size_t after,
                                                               const exec::TravelCache& travel) {
  std::optional<std::pair<std::size_t, Duration>> best;
  for (std::size_t at = after; at <= way.stops.size(); ++at) {
    std::vector<Stop> stops = way.stops;
    stops.insert(stops.begin() + static_cast<std::ptrdiff_t>(at), stop);
    const std::optional<Duration> d = way_travel(way.from, way.free, stops, travel);
    if (d && (!best || *d < best->second)) best = std::pair{at, *d};
  }
  return best;
}

// When the robot could be at the task's place: when it is next free (at `from` at `free`), plus
// its way there.
Duration soonest_there(const Task& t, map::NodeIndex from, Time free, const exec::Building& building) {
  const auto node = t.start_node.empty() ? std::optional<map::NodeIndex>(from) : building.map.find_node(t.start_node);
  const Duration to = node ? building.travel.travel(from, *node, free) : exec::kUnreachable;
  return (free - building.clock.now()) + to;
}
Duration soonest_there(const Task& t, const Way& way, const exec::Building& building) {
  return soonest_there(t, way.from, way.free, building);
}

// How an on-demand task would start on a robot, best first: a free robot (0) goes now; one running
// an interruptible standard task (1) interrupts it, the lowest priority first; any other (2) starts
// it when it is next free. Then by how soon the robot could be at the task's place.
struct OnDemandRank {
  int how = 2;
  int priority = 0;  // of the task it would interrupt
  Duration arrival{0};
  auto operator<=>(const OnDemandRank&) const = default;
};
OnDemandRank on_demand_rank(const Task& t, const exec::Executor& robot, const Way& way,
                            const exec::Building& building) {
  if (robot.activity().on_demand.empty()) {
    if (const std::optional<TaskId> run = robot.preemptible_run()) {
      const exec::TaskRecord* r = building.book.find(*run);
      return {1, r ? r->task.priority : 0, soonest_there(t, robot.robot().location(), building.clock.now(), building)};
    }
    if (!robot.current_task() || robot.phase() == exec::ExecutorPhase::kWaiting)
      return {0, 0, soonest_there(t, way, building)};
  }
  return {2, 0, soonest_there(t, way, building)};
}

// What a unit costs on a robot's way: the expected travel it adds at its best positions (a drop
// after its pickup), where every stop still starts in its window; nothing when it fits nowhere.
struct Insertion {
  Duration cost{0};
  std::vector<std::pair<std::size_t, Stop>> inserts;  // position, stop: applied in order
};
std::optional<Insertion> insertion(const AllocationUnit& unit, const Way& way, const exec::Building& building) {
  const std::optional<Duration> before = way_travel(way.from, way.free, way.stops, building.travel);
  if (!before) return std::nullopt;
  Way trial = way;
  Insertion out;
  std::size_t after = 0;
  for (const Task* t : unit.tasks) {
    const std::optional<Stop> stop = stop_of(*t, nullptr, building);
    if (!stop) return std::nullopt;
    const auto at = best_insertion(trial, *stop, after, building.travel);
    if (!at) return std::nullopt;
    trial.stops.insert(trial.stops.begin() + static_cast<std::ptrdiff_t>(at->first), *stop);
    out.inserts.emplace_back(at->first, *stop);
    after = at->first + 1;
    out.cost = at->second - *before;
  }
  return out;
}

// Why `chosen` over the others: its cost, and the next robots' (at most three), fitting ones first.
struct Option {
  std::size_t robot = 0;
  bool fits = false;
  Duration cost{0};
  OnDemandRank rank{};  // an on-demand task's
};
std::string explain(const Option& chosen, std::vector<Option> others, bool on_demand,
                    const std::vector<const exec::Executor*>& robots) {
  std::stable_sort(others.begin(), others.end(), [on_demand](const Option& a, const Option& b) {
    if (on_demand) return a.rank < b.rank;
    return a.fits != b.fits ? a.fits : a.cost < b.cost;
  });
  std::string rest;
  for (std::size_t i = 0; i < others.size() && i < 3; ++i) {
    const Option& o = others[i];
    const bool unreachable = o.cost >= exec::kUnreachable;
    rest += fmt::format(
        "{}{}: {}", rest.empty() ? "" : ", ", robots[o.robot]->name(),
        o.fits || on_demand ? (unreachable ? "cannot get there" : format_duration(o.cost)) : "does not fit");
  }
  if (others.size() > 3) rest += fmt::format(", {} more", others.size() - 3);
  const std::optional<TaskId> interrupts = on_demand ? robots[chosen.robot]->preemptible_run() : std::nullopt;
  const bool idle = on_demand && chosen.rank.how == 0;
  const std::string head =
      on_demand ? fmt::format("{} can be there soonest, in {}",
                              idle         ? "of the free robots it"
                              : interrupts ? fmt::format("no robot is free; interrupting task {} (priority {}), it",
                                                         *interrupts, chosen.rank.priority)
                                           : "no robot is free or can be interrupted; it",
                              format_duration(chosen.cost))
      : chosen.fits
          ? fmt::format("it adds least travel to its schedule, {}", format_duration(chosen.cost))
          : fmt::format("it fits no robot's schedule and could be there soonest, in {}", format_duration(chosen.cost));
  return rest.empty() ? head : fmt::format("{} ({})", head, rest);
}

}  // namespace

// An object that stays on board (its returns failed) would otherwise draw every look-alike job to a
// robot that must drop each of them.
bool room_on_board(const AllocationUnit& unit, const exec::Executor& robot) {
  int load = 0;
  for (const Task* t : unit.tasks)
    if (t->delivery && t->delivery->role == DeliveryRole::kPickup) load += t->delivery->load;
  if (load == 0) return true;
  const std::vector<exec::OnBoard> on_board = robot.on_board();
  int carried = 0;
  for (const exec::OnBoard& o : on_board) {
    carried += o.load;
    for (const Task* t : unit.tasks)
      if (t->delivery && !t->delivery->appearance.empty() && t->delivery->appearance == o.appearance) return false;
  }
  return robot.capacity() <= 0 || carried + load <= robot.capacity();
}


std::vector<Allocation> GreedyAllocator::allocate(const std::vector<AllocationUnit>& units,
                                                  const std::vector<const exec::Executor*>& robots,
                                                  const exec::Building& building) {
  std::map<std::size_t, Way> ways;  // built when a unit has a choice to make
  auto way_of = [&](std::size_t r) -> Way& {
    auto it = ways.find(r);
    if (it != ways.end()) return it->second;
    Way w;
    std::tie(w.from, w.free) = robots[r]->free_at();
    for (const TaskId& id : robots[r]->activity().planned) {
      const exec::TaskRecord* rec = building.book.find(id);
      if (!rec) continue;
      if (auto s = stop_of(rec->task, rec, building)) w.stops.push_back(*s);
    }
    return ways.emplace(r, std::move(w)).first->second;
  };

  std::vector<Allocation> chosen;
  chosen.reserve(units.size());
  if (robots.size() == 1) {  // a fleet of one: nothing to choose, nothing to move
    chosen.assign(units.size(), Allocation{.robot = 0, .fits = true, .why = "the only robot"});
    return chosen;
  }
  for (const AllocationUnit& unit : units) {
    const bool on_demand =
        std::any_of(unit.tasks.begin(), unit.tasks.end(), [](const Task* t) { return t->kind == TaskKind::kOnDemand; });
    // Every eligible robot's cost: one the unit fits ranks before every one it does not; then by
    // cost (added travel where it fits, else how soon the robot could be there).
    std::vector<Option> options;
    std::optional<std::size_t> best;
    std::vector<std::pair<std::size_t, Stop>> best_inserts;
    for (const std::size_t r : unit.eligible) {
      const Way& way = way_of(r);
      std::optional<Insertion> fit =
          on_demand || !room_on_board(unit, *robots[r]) ? std::nullopt : insertion(unit, way, building);
      const bool fits = fit.has_value();
      const OnDemandRank rank =
          on_demand ? on_demand_rank(*unit.tasks.front(), *robots[r], way, building) : OnDemandRank{};
      const Duration cost = fits        ? fit->cost
                            : on_demand ? rank.arrival
                                        : soonest_there(*unit.tasks.front(), way, building);
      options.push_back({r, fits, cost, rank});
      const Option* b = best ? &options[*best] : nullptr;
      const bool better =
          !b || (on_demand ? rank < b->rank : (fits && !b->fits) || (fits == b->fits && cost < b->cost));
      if (better) {
        best = options.size() - 1;
        best_inserts = fits ? std::move(fit->inserts) : decltype(best_inserts){};
      }
    }
    const Option pick = best ? options[*best] : Option{unit.eligible.front(), false, Duration{0}};
    options.erase(options.begin() + static_cast<std::ptrdiff_t>(best.value_or(0)));
    // The unit is on that robot's way now, for the units after it.
    Way& way = way_of(pick.robot);
    for (const auto& [at, stop] : best_inserts)
      way.stops.insert(way.stops.begin() + static_cast<std::ptrdiff_t>(at), stop);
    const std::string why = unit.eligible.size() == 1 ? "the only robot that may take it"
                                                      : explain(pick, std::move(options), on_demand, robots);
    chosen.push_back({.robot = pick.robot, .fits = pick.fits || on_demand, .why = why});
  }
  return chosen;
}

}  // namespace rondo::fleet
