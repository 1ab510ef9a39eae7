#include "rondo/exec/map_travel.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "rondo/plan/mdp.h"
#include "rondo/plan/policy.h"

namespace rondo::exec {
namespace {

Duration to_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds >= to_seconds(kUnreachable)) return kUnreachable;
  return Duration{static_cast<std::int64_t>(std::llround(seconds * 1000.0))};
}

// Departures only move forward: entries a day older than the slot asked for are not asked again.
template <class Entries>
void drop_behind(Entries& entries, Time slot_start) {
  if (!entries.empty() && entries.begin()->first.first < slot_start - kTravelKeepBehind)
    entries.erase(entries.begin(), entries.lower_bound({slot_start - kTravelKeepBehind, 0}));
}

// Erases the entries read longest ago (by generation; within one, the earlier key) until at most
// `bound` are left; returns how many went.
template <class Entries>
std::size_t evict_least_recent(Entries& entries, std::size_t bound) {
  if (entries.size() <= bound) return 0;
  using Item = std::pair<std::uint64_t, typename Entries::iterator>;
  std::vector<Item> order;
  order.reserve(entries.size());
  for (auto it = entries.begin(); it != entries.end(); ++it) order.emplace_back(it->second.used, it);
  const std::size_t excess = entries.size() - bound;
  std::nth_element(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(excess - 1), order.end(),
                   [](const Item& a, const Item& b) {
                     return a.first != b.first ? a.first < b.first : a.second->first < b.second->first;
                   });
  for (std::size_t i = 0; i < excess; ++i) entries.erase(order[i].second);
  return excess;
}

template <class Sets>
std::size_t count_bound(const Sets& recent) {
  const std::size_t largest = *std::max_element(recent.begin(), recent.end());
  return std::max(kTravelCacheFloor, kTravelCacheWorkingSets * largest);
}

// Whether the time-dependent value replaces the departure slot's: they differ by more than the
// threshold (one reachable and the other not counts as more).
bool along_the_route(double route_seconds, double slot_seconds, Duration threshold) {
  if (std::isfinite(route_seconds) != std::isfinite(slot_seconds)) return true;
  return std::isfinite(route_seconds) && std::abs(route_seconds - slot_seconds) > to_seconds(threshold);
}

}  // namespace

TravelCache::TravelCache(const map::TopoMap& map, std::shared_ptr<const plan::EdgeModelView> models,
                         plan::TravelPlanner& planner, Duration slot_width, std::optional<Duration> route_threshold)
    : map_(&map),
      models_(std::move(models)),
      planner_(&planner),
      slot_width_(slot_width),
      route_threshold_(route_threshold) {}

bool TravelCache::refresh(Entry& entry, Time slot_start) const {
  const std::uint64_t now = models_->version();
  if (entry.version == now) return true;
  const std::optional<std::vector<map::EdgeIndex>> changed = models_->changed_since(entry.version);
  if (!changed) return false;
  if (!changed->empty()) {
    // The planner's M_t re-reads just these edges at the slot start.
    const std::shared_ptr<const plan::Mdp> mdp = planner_->mdp_at(slot_start);
    for (map::EdgeIndex e : *changed) {
      if (!entry.policy.survives_edge_change(e, map_->from_index(e), map_->to_index(e),
                                             mdp->expected_crossing_seconds(e)))
        return false;
    }
  }
  entry.version = now;
  return true;
}

template <class E>
E& TravelCache::touch(E& entry, WorkingSets& sets) const {
  if (entry.used != generation_) {
    entry.used = generation_;
    ++sets[generation_ % kRecentGenerations];
  }
  return entry;
}

const TravelCache::Arrivals& TravelCache::arrivals(map::NodeIndex from, Time slot_start) const {
  const auto key = std::make_pair(slot_start, from);
  auto it = arrivals_.find(key);
  if (it == arrivals_.end()) {
    drop_behind(arrivals_, slot_start);
    it = arrivals_.emplace(key, Arrivals{}).first;
  }
  Arrivals& r = it->second;
  // Any change may move an arrival (the edges are read in many slots): searched again.
  if (r.arrival_seconds.empty() || r.version != models_->version()) {
    ++route_searches_;
    r.arrival_seconds = planner_->time_dependent_arrivals(from, slot_start);
    r.version = models_->version();
  }
  return touch(r, recent_arrival_sets_);
}

TravelCache::Entry& TravelCache::entry(map::NodeIndex to, Time slot_start) const {
  const auto key = std::make_pair(slot_start, to);
  auto it = policies_.find(key);
  if (it != policies_.end()) {
    if (refresh(it->second, slot_start)) {
      ++kept_;
      return touch(it->second, recent_sets_);
    }
    ++resolved_;
    ++solved_;
    it->second.policy = planner_->solve_policy(to, slot_start);
    it->second.version = models_->version();
    it->second.quantile_seconds.clear();
    return touch(it->second, recent_sets_);
  }
  drop_behind(policies_, slot_start);
  ++solved_;
  return touch(policies_.emplace(key, Entry{planner_->solve_policy(to, slot_start), models_->version()}).first->second,
               recent_sets_);
}

void TravelCache::begin_problem() const {
  ++generation_;
  recent_sets_[generation_ % kRecentGenerations] = 0;
  recent_arrival_sets_[generation_ % kRecentGenerations] = 0;
  evict_to_bound();
}

void TravelCache::evict_to_bound() const {
  // A new generation has read nothing yet, and the previous one's entries sort last, within the
  // bound (>= its size).
  evicted_ += evict_least_recent(policies_, count_bound(recent_sets_));
  evict_least_recent(arrivals_, count_bound(recent_arrival_sets_));
}

Duration TravelCache::at_slot(map::NodeIndex from, map::NodeIndex to, Time slot_start) const {
  if (from == to) return Duration{0};
  const double slot_seconds = policy(to, slot_start).expected_seconds(from);
  if (!route_threshold_) return to_duration(slot_seconds);
  const double route_seconds = arrivals(from, slot_start).arrival_seconds[to];
  return to_duration(along_the_route(route_seconds, slot_seconds, *route_threshold_) ? route_seconds : slot_seconds);
}

Duration TravelCache::quantile_at_slot(map::NodeIndex from, map::NodeIndex to, Time slot_start, double level) const {
  if (from == to) return Duration{0};
  Entry& e = entry(to, slot_start);
  if (e.quantile_seconds.empty() || e.level != level) {
    e.level = level;
    e.quantile_seconds.assign(map_->node_count(), std::numeric_limits<double>::quiet_NaN());
  }
  double& q = e.quantile_seconds[from];
  if (std::isnan(q)) {
    // A coarser grid than the default: the bracket is still an upper bound, within ~1.6 % of the
    // expected time per expected attempt, and a route's distribution costs a quarter. Its first
    // quarter (4 x the expected time) is computed first, and the whole grid only for a quantile
    // beyond it: the same answer to the bit (DistributionOptions::computed_cells), for a quarter
    // of the work where the quantile is within.
    const auto laws = [&](const plan::PolicyStep& s, plan::RouteLeg& leg) {
      models_->attempt_laws(s.edge, slot_start, leg);
    };
    plan::DistributionOptions grid{.cells = 1024, .horizon_factor = 16.0, .computed_cells = 256};
    plan::TravelTimeDistribution d = e.policy.travel_time_distribution(from, grid, laws);
    if (d.reachable() && !std::isfinite(d.quantile(level).upper)) {
      grid.computed_cells = 0;
      d = e.policy.travel_time_distribution(from, grid, laws);
    }
    // A quantile beyond the grid (16 x the expected time) is read as the grid's end: a reachable
    // target stays reachable for the window check.
    const double upper = d.quantile(level).upper;
    q = !d.reachable() ? std::numeric_limits<double>::infinity()
                       : (std::isfinite(upper) ? upper : d.horizon_seconds());
  }
  return to_duration(q);
}

std::uint64_t TravelCache::models_version() const {
  return models_->version();
}

Duration TravelCache::travel(map::NodeIndex from, map::NodeIndex to, Time depart) const {
  if (from == to) return Duration{0};
  return interpolate(depart, [&](Time slot) { return at_slot(from, to, slot); });
}

Duration TravelCache::quantile_travel(map::NodeIndex from, map::NodeIndex to, Time depart, double level) const {
  if (from == to) return Duration{0};
  return interpolate(depart, [&](Time slot) { return quantile_at_slot(from, to, slot, level); });
}

double TravelCache::edge_week_min(map::EdgeIndex e) const {
  // Every slot start of a week from when the edge's answers stop depending on anything but the
  // time of week, and the ones before that (they may depend on the time since its last attempt).
  double m = std::numeric_limits<double>::infinity();
  const Time from = planner_->slot_start(models_->conditioned_until(e));
  for (Time t = from; t < from + hours(24 * 7) + models_->memory(); t += slot_width_)
    m = std::min(m, plan::expected_crossing_seconds(plan::sanitize(models_->outcome(e, t))));
  return m;
}

void TravelCache::refresh_lower_bounds() const {
  const std::uint64_t now = models_->version();
  if (!edge_min_seconds_.empty() && lower_version_ == now) return;
  const std::optional<std::vector<map::EdgeIndex>> changed =
      edge_min_seconds_.empty() ? std::nullopt : models_->changed_since(lower_version_);
  lower_version_ = now;
  if (!changed) {
    edge_min_seconds_.resize(map_->edge_count());
    for (map::EdgeIndex e = 0; e < map_->edge_count(); ++e) edge_min_seconds_[e] = edge_week_min(e);
    lower_from_.clear();
    return;
  }
  for (map::EdgeIndex e : *changed) {
    const double m = edge_week_min(e);
    if (m == edge_min_seconds_[e]) continue;
    edge_min_seconds_[e] = m;
    lower_from_.clear();
  }
}

Duration TravelCache::lower_bound(map::NodeIndex from, map::NodeIndex to) const {
  if (from == to) return Duration{0};
  refresh_lower_bounds();
  const std::size_t n = map_->node_count();
  auto it = lower_from_.find(from);
  if (it == lower_from_.end()) {
    std::vector<double> dist(n, std::numeric_limits<double>::infinity());
    using Item = std::pair<double, map::NodeIndex>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> heap;
    dist[from] = 0;
    heap.emplace(0.0, from);
    while (!heap.empty()) {
      const auto [d, u] = heap.top();
      heap.pop();
      if (d > dist[u]) continue;
      for (map::EdgeIndex e : map_->out_edges(u)) {
        const map::NodeIndex v = map_->to_index(e);
        const double nd = d + edge_min_seconds_[e];
        if (nd < dist[v]) {
          dist[v] = nd;
          heap.emplace(nd, v);
        }
      }
    }
    it = lower_from_.emplace(from, std::move(dist)).first;
  }
  const double s = it->second[to];
  if (!std::isfinite(s)) return kUnreachable;
  return Duration{static_cast<std::int64_t>(std::floor(s * 1000.0))};
}

std::int64_t* SlotTable::cell(Time slot_start, Duration slot_width, std::size_t from, std::size_t to) {
  if (slots_.empty()) first_ = slot_start;
  if (slot_start < first_) {  // an earlier slot than any read yet: rows go in at the front
    if ((first_ - slot_start) % slot_width != Duration{0}) return nullptr;
    slots_.insert(slots_.begin(), static_cast<std::size_t>((first_ - slot_start) / slot_width), {});
    first_ = slot_start;
  }
  const std::int64_t offset = (slot_start - first_).count(), width = slot_width.count();
  const auto slot = static_cast<std::size_t>(offset / width);
  if (static_cast<std::int64_t>(slot) * width != offset) return nullptr;
  if (slot >= slots_.size()) slots_.resize(slot + 1);
  std::vector<std::vector<std::int64_t>>& rows = slots_[slot];
  if (rows.empty()) rows.resize(locations_);
  std::vector<std::int64_t>& row = rows[from];
  if (row.empty()) row.assign(locations_, kNotRead);
  return &row[to];
}

namespace {

// A standard time as a robot of factor `speed` takes it.
Duration at_speed(Duration standard, double speed) {
  if (speed == 1.0 || standard >= kUnreachable) return standard;
  return Duration{static_cast<std::int64_t>(std::llround(static_cast<double>(standard.count()) / speed))};
}

}  // namespace

SchedulerQuantileTravel::SchedulerQuantileTravel(const TravelCache& cache, std::vector<map::NodeIndex> nodes,
                                                 double level, double speed)
    : cache_(&cache), nodes_(std::move(nodes)), level_(level), speed_(speed), values_(nodes_.size()) {}

Duration SchedulerQuantileTravel::travel(schedule::LocationIndex from, schedule::LocationIndex to, Time depart) const {
  const map::NodeIndex a = nodes_[from], b = nodes_[to];
  if (a == b) return Duration{0};
  const std::uint64_t version = cache_->models_version();
  return cache_->interpolate(depart, [&](Time slot) {
    return values_.get(version, slot, cache_->slot_width(), from, to,
                       [&] { return at_speed(cache_->quantile_at_slot(a, b, slot, level_), speed_); });
  });
}

SchedulerTravel::SchedulerTravel(const TravelCache& cache, std::vector<map::NodeIndex> nodes, double speed)
    : cache_(&cache), nodes_(std::move(nodes)), speed_(speed), values_(nodes_.size()) {
  cache_->begin_problem();
}

Duration SchedulerTravel::travel(schedule::LocationIndex from, schedule::LocationIndex to, Time depart) const {
  const map::NodeIndex a = nodes_[from], b = nodes_[to];
  if (a == b) return Duration{0};
  const std::uint64_t version = cache_->models_version();
  return cache_->interpolate(depart, [&](Time slot) {
    return values_.get(version, slot, cache_->slot_width(), from, to,
                       [&] { return at_speed(cache_->at_slot(a, b, slot), speed_); });
  });
}

Duration SchedulerTravel::lower_bound(schedule::LocationIndex from, schedule::LocationIndex to) const {
  return at_speed(cache_->lower_bound(nodes_[from], nodes_[to]), speed_);
}

}  // namespace rondo::exec
