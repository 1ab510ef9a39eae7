#include "rondo/exec/map_travel.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "rondo/plan/mdp.h"

namespace rondo::exec {
namespace {

Duration to_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds >= to_seconds(kUnreachable)) return kUnreachable;
  return Duration{static_cast<std::int64_t>(std::llround(seconds * 1000.0))};
}

}  // namespace

TravelCache::TravelCache(const map::TopoMap& map, std::shared_ptr<const plan::EdgeModelView> models,
                         plan::TravelOracle& planner, Duration slot_width)
    : map_(&map), models_(std::move(models)), planner_(&planner), slot_width_(slot_width) {
  version_ = models_->version();
}

void TravelCache::check_version() const {
  if (models_->version() == version_) return;
  version_ = models_->version();
  values_.clear();
  edge_min_seconds_.clear();
  lower_from_.clear();
}

Duration TravelCache::at_slot(map::NodeIndex from, map::NodeIndex to, Time slot_start) const {
  check_version();
  if (from == to) return Duration{0};
  const auto key = std::make_tuple(slot_start, from, to);
  if (auto it = values_.find(key); it != values_.end()) return it->second;
  const Duration d = to_duration(planner_->expected_seconds(from, to, slot_start));
  values_.emplace(key, d);
  return d;
}

Duration TravelCache::travel(map::NodeIndex from, map::NodeIndex to, Time depart) const {
  if (from == to) return Duration{0};
  const Time start = planner_->slot_start(depart);
  const Time next = start + slot_width_;
  const Duration here = at_slot(from, to, start);
  if (here >= kUnreachable) return kUnreachable;
  Duration there = at_slot(from, to, next);
  if (there >= kUnreachable) return here;  // closed later: the value now holds within the slot
  there = std::max(there, here - slot_width_);  // FIFO: slope >= -1
  const double f = static_cast<double>((depart - start).count()) / static_cast<double>(slot_width_.count());
  const double ms = static_cast<double>(here.count()) + f * static_cast<double>((there - here).count());
  return Duration{static_cast<std::int64_t>(std::llround(ms))};
}

Duration TravelCache::lower_bound(map::NodeIndex from, map::NodeIndex to) const {
  check_version();
  if (from == to) return Duration{0};
  const std::size_t n = map_->node_count();
  if (edge_min_seconds_.empty()) {
    edge_min_seconds_.assign(map_->edge_count(), std::numeric_limits<double>::infinity());
    const Time week_start = planner_->slot_start(Time{});
    for (Time t = week_start; t < week_start + hours(24 * 7); t += slot_width_)
      for (map::EdgeIndex e = 0; e < map_->edge_count(); ++e) {
        const double c = plan::expected_crossing_seconds(plan::sanitize(models_->outcome(e, t)));
        edge_min_seconds_[e] = std::min(edge_min_seconds_[e], c);
      }
  }
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

MapTravel::MapTravel(const TravelCache& cache, std::vector<map::NodeIndex> nodes)
    : cache_(&cache), nodes_(std::move(nodes)) {}

Duration MapTravel::travel(schedule::LocationIndex from, schedule::LocationIndex to, Time depart) const {
  return cache_->travel(nodes_[from], nodes_[to], depart);
}

Duration MapTravel::lower_bound(schedule::LocationIndex from, schedule::LocationIndex to) const {
  return cache_->lower_bound(nodes_[from], nodes_[to]);
}

}  // namespace rondo::exec
