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

}  // namespace

std::vector<std::size_t> GreedyAllocator::allocate(const std::vector<AllocationUnit>& units,
                                                   const std::vector<const exec::Executor*>& robots,
                                                   const exec::Building& building) {
  const exec::TravelCache& travel = building.travel;
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
    std::optional<std::size_t> best;
    Duration best_cost = Duration::max();
    bool best_fits = false;
    std::vector<std::pair<std::size_t, Stop>> best_inserts;
    for (const std::size_t r : unit.eligible) {
      Way& way = way_of(r);
      if (on_demand) {
        // Soonest there: when the robot is next free, plus its way to the task's place.
        const Task& t = *unit.tasks.front();
        const auto node =
            t.start_node.empty() ? std::optional<map::NodeIndex>(way.from) : building.map.find_node(t.start_node);
        const Duration to = node ? travel.travel(way.from, *node, way.free) : exec::kUnreachable;
        const Duration cost = (way.free - building.clock.now()) + to;
        if (!best || cost < best_cost) {
          best = r;
          best_cost = cost;
        }
        continue;
      }
      const std::optional<Duration> before = way_travel(way.from, way.free, way.stops, travel);
      Way trial = way;
      std::vector<std::pair<std::size_t, Stop>> inserts;
      bool fits = before.has_value();
      std::size_t after = 0;
      Duration cost{0};
      for (const Task* t : unit.tasks) {
        const std::optional<Stop> stop = stop_of(*t, nullptr, building);
        if (!stop) {
          fits = false;
          break;
        }
        const auto at = fits ? best_insertion(trial, *stop, after, travel) : std::nullopt;
        if (!at) {
          fits = false;
          break;
        }
        trial.stops.insert(trial.stops.begin() + static_cast<std::ptrdiff_t>(at->first), *stop);
        inserts.emplace_back(at->first, *stop);
        after = at->first + 1;
        cost = at->second - *before;
      }
      if (!fits) {
        // Fits nowhere: ranked after every robot it fits, by when this robot could first get there.
        const Task& t = *unit.tasks.front();
        const auto node = building.map.find_node(t.start_node);
        cost =
            (way.free - building.clock.now()) + (node ? travel.travel(way.from, *node, way.free) : exec::kUnreachable);
      }
      if (!best || (fits && !best_fits) || (fits == best_fits && cost < best_cost)) {
        best = r;
        best_cost = cost;
        best_fits = fits;
        best_inserts = fits ? inserts : decltype(inserts){};
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
