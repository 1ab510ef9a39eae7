#include <algorithm>
#include <limits>
#include <map>
#include <optional>

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

// When the robot could be at the task's place: when it is next free, plus its way there.
Duration soonest_there(const Task& t, const Way& way, const exec::Building& building) {
  const auto node =
      t.start_node.empty() ? std::optional<map::NodeIndex>(way.from) : building.map.find_node(t.start_node);
  const Duration to = node ? building.travel.travel(way.from, *node, way.free) : exec::kUnreachable;
  return (way.free - building.clock.now()) + to;
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

}  // namespace

std::vector<std::size_t> GreedyAllocator::allocate(const std::vector<AllocationUnit>& units,
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

  std::vector<std::size_t> chosen;
  chosen.reserve(units.size());
  for (const AllocationUnit& unit : units) {
    if (unit.eligible.size() == 1) {
      chosen.push_back(unit.eligible.front());
      continue;
    }
    const bool on_demand =
        std::any_of(unit.tasks.begin(), unit.tasks.end(), [](const Task* t) { return t->kind == TaskKind::kOnDemand; });
    // The best robot so far: one the unit fits ranks before every one it does not; then by cost
    // (added travel where it fits, else how soon the robot could be there).
    std::optional<std::size_t> best;
    Duration best_cost = Duration::max();
    bool best_fits = false;
    std::vector<std::pair<std::size_t, Stop>> best_inserts;
    for (const std::size_t r : unit.eligible) {
      const Way& way = way_of(r);
      std::optional<Insertion> fit = on_demand ? std::nullopt : insertion(unit, way, building);
      const bool fits = fit.has_value();
      const Duration cost = fits ? fit->cost : soonest_there(*unit.tasks.front(), way, building);
      if (!best || (fits && !best_fits) || (fits == best_fits && cost < best_cost)) {
        best = r;
        best_cost = cost;
        best_fits = fits;
        best_inserts = fits ? std::move(fit->inserts) : decltype(best_inserts){};
      }
    }
    const std::size_t r = best.value_or(unit.eligible.front());
    // The unit is on that robot's way now, for the units after it.
    Way& way = way_of(r);
    for (const auto& [at, stop] : best_inserts)
      way.stops.insert(way.stops.begin() + static_cast<std::ptrdiff_t>(at), stop);
    chosen.push_back(r);
  }
  return chosen;
}

}  // namespace rondo::fleet
