#include "rondo/sim/replay_world.h"

#include <algorithm>

namespace rondo::sim {
namespace {

constexpr Duration kWeek = std::chrono::days(7);

std::int64_t local_day_number(const TimeZone& zone, Time t) {
  return std::chrono::sys_days(zone.local_date(t)).time_since_epoch().count();
}

std::optional<map::EdgeIndex> match_edge(const map::TopoMap& map, const Traversal& t) {
  if (auto e = map.find_edge(t.edge_id)) return e;
  const auto from = map.find_node(t.from);
  if (!from) return std::nullopt;
  for (map::EdgeIndex e : map.out_edges(*from)) {
    if (map.edge(e).to == t.to) return e;
  }
  return std::nullopt;
}

// Appends the attempts with time of week in [lo, hi] (both inside [0, kWeek)).
void append_range(const std::vector<LoggedAttempt>& sorted, Duration lo, Duration hi,
                  std::vector<const LoggedAttempt*>& out) {
  auto first = std::lower_bound(sorted.begin(), sorted.end(), lo,
                                [](const LoggedAttempt& a, Duration d) { return a.time_of_week < d; });
  for (auto it = first; it != sorted.end() && it->time_of_week <= hi; ++it) out.push_back(&*it);
}

}  // namespace

std::int64_t week_number(const TimeZone& zone, Time t) {
  constexpr std::int64_t kFirstMonday = 4;  // 1970-01-05 is day 4 of the Unix epoch
  const std::int64_t days = local_day_number(zone, t) - kFirstMonday;
  return days >= 0 ? days / 7 : -((-days + 6) / 7);
}

ReplayWorld::ReplayWorld(const map::TopoMap& map, const std::vector<Traversal>& log, TimeZone zone,
                         ReplayOptions options)
    : zone_(std::move(zone)),
      options_(std::move(options)),
      prior_(map, zone_, options_.prior),
      by_edge_(map.edge_count()) {
  for (const Traversal& t : log) {
    const auto edge = match_edge(map, t);
    if (!edge) {
      ++unmatched_;
      continue;
    }
    by_edge_[*edge].push_back({t.start, t.duration, t.success, options_.log_zone.time_of_week(t.start) % kWeek,
                               week_number(options_.log_zone, t.start)});
    weeks_.push_back(by_edge_[*edge].back().week);
  }
  for (auto& attempts : by_edge_) {
    std::stable_sort(attempts.begin(), attempts.end(),
                     [](const LoggedAttempt& a, const LoggedAttempt& b) { return a.time_of_week < b.time_of_week; });
  }
  std::sort(weeks_.begin(), weeks_.end());
  weeks_.erase(std::unique(weeks_.begin(), weeks_.end()), weeks_.end());
}

std::vector<const LoggedAttempt*> ReplayWorld::near(map::EdgeIndex edge, Duration time_of_week,
                                                    Duration half_width) const {
  const auto& sorted = by_edge_.at(edge);
  std::vector<const LoggedAttempt*> out;
  if (half_width * 2 >= kWeek) {
    for (const auto& a : sorted) out.push_back(&a);
    return out;
  }
  const Duration q = ((time_of_week % kWeek) + kWeek) % kWeek;
  const Duration lo = q - half_width;
  const Duration hi = q + half_width;
  if (lo < Duration{0}) {
    append_range(sorted, Duration{0}, hi, out);
    append_range(sorted, lo + kWeek, kWeek, out);
  } else if (hi >= kWeek) {
    append_range(sorted, Duration{0}, hi - kWeek, out);
    append_range(sorted, lo, kWeek, out);
  } else {
    append_range(sorted, lo, hi, out);
  }
  return out;
}

std::int64_t ReplayWorld::week_for_day(Time t, Rng& rng) {
  const std::int64_t day = local_day_number(zone_, t);
  auto it = week_of_day_.find(day);
  if (it != week_of_day_.end()) return it->second;
  const std::int64_t week = weeks_.empty() ? 0 : weeks_[rng.uniform_int(weeks_.size())];
  week_of_day_.emplace(day, week);
  return week;
}

const LoggedAttempt* ReplayWorld::draw(map::EdgeIndex edge, Time start, Rng& rng) {
  if (by_edge_.at(edge).empty()) return nullptr;
  const std::int64_t week = week_for_day(start, rng);
  const Duration tow = zone_.time_of_week(start);
  for (Duration half = options_.window > Duration{0} ? options_.window : minutes(30);; half *= 2) {
    const auto candidates = near(edge, tow, half);
    if (candidates.empty()) continue;  // the loop ends: a half-width of half a week takes them all
    std::vector<const LoggedAttempt*> same_week;
    for (const LoggedAttempt* a : candidates) {
      if (a->week == week) same_week.push_back(a);
    }
    const auto& pool = same_week.empty() ? candidates : same_week;
    return pool[rng.uniform_int(pool.size())];
  }
}

EdgeSample ReplayWorld::sample_edge(map::EdgeIndex edge, Time start, Rng& rng) {
  const LoggedAttempt* a = draw(edge, start, rng);
  if (a == nullptr) return prior_.sample_edge(edge, start, rng);
  return {a->success, std::max(a->duration, Duration{0})};
}

}  // namespace rondo::sim
