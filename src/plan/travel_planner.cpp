#include "rondo/plan/travel_planner.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <stdexcept>
#include <string>
#include <utility>

#include "rondo/plan/exact_solver.h"

namespace rondo::plan {
namespace {

void check_node(const map::TopoMap& map, NodeIndex node) {
  if (node >= map.node_count()) {
    throw std::out_of_range("TravelPlanner: node index " + std::to_string(node) + " is not in the map");
  }
}

}  // namespace

TravelPlanner::TravelPlanner(const map::TopoMap& map, std::shared_ptr<const EdgeModelView> models,
                           const TravelPlannerOptions& options)
    : map_(&map),
      models_(std::move(models)),
      options_(options),
      dead_ends_(std::make_shared<const DeadEnds>(DeadEnds::find(map))) {
  if (!models_) throw std::invalid_argument("TravelPlanner: no edge models");
  if (options_.slot_width <= Duration::zero()) throw std::invalid_argument("TravelPlanner: slot width must be > 0");
  options_.max_cached_policies = std::max<std::size_t>(options_.max_cached_policies, 1);
  options_.max_cached_slots = std::max<std::size_t>(options_.max_cached_slots, 1);
}

std::int64_t TravelPlanner::slot_of(Time t) const {
  const std::int64_t ms = t.time_since_epoch().count();
  const std::int64_t w = options_.slot_width.count();
  return ms >= 0 ? ms / w : -((-ms + w - 1) / w);  // floor division
}

Time TravelPlanner::slot_start(Time t) const {
  return Time{options_.slot_width * slot_of(t)};
}

bool TravelPlanner::refresh(CachedMdp& entry) {
  const std::uint64_t now = models_->version();
  if (entry.version == now) return true;
  const std::optional<std::vector<EdgeIndex>> changed = models_->changed_since(entry.version);
  if (!changed) return false;
  const Mdp& old = *entry.mdp;
  std::vector<std::pair<EdgeIndex, EdgeCrossing>> patches;
  for (EdgeIndex e : *changed) {
    const EdgeCrossing o = sanitize(models_->outcome(e, old.time()));
    if (!(o == old.outcome(e))) patches.emplace_back(e, o);
  }
  if (!patches.empty()) {
    std::vector<EdgeCrossing> outcomes;
    outcomes.reserve(old.edge_count());
    for (EdgeIndex e = 0; e < old.edge_count(); ++e) outcomes.push_back(old.outcome(e));
    for (const auto& [e, o] : patches) outcomes[e] = o;
    entry.mdp =
        std::make_shared<const Mdp>(Mdp::from_outcomes(*map_, std::move(outcomes), old.time(), dead_ends_).value());
  }
  entry.version = now;
  return true;
}

const std::shared_ptr<const Mdp>& TravelPlanner::slot_entry(std::int64_t slot) {
  auto it = slots_.find(slot);
  if (it != slots_.end() && refresh(it->second)) return it->second.mdp;
  if (it == slots_.end()) {
    if (options_.keep_behind)
      slots_.erase(slots_.begin(), slots_.lower_bound(slot - options_.keep_behind->count() / options_.slot_width.count()));
    if (slots_.size() >= options_.max_cached_slots) slots_.clear();
    it = slots_.emplace(slot, CachedMdp{}).first;
  }
  const Time at{options_.slot_width * slot};
  it->second = {std::make_shared<const Mdp>(Mdp::build(*map_, *models_, at, dead_ends_)), models_->version()};
  return it->second.mdp;
}

std::shared_ptr<const Mdp> TravelPlanner::mdp_at(Time depart) {
  return slot_entry(slot_of(depart));
}

bool TravelPlanner::refresh(CachedPolicy& entry, std::int64_t slot) {
  const std::uint64_t now = models_->version();
  if (entry.version == now) return true;
  const std::optional<std::vector<EdgeIndex>> changed = models_->changed_since(entry.version);
  if (!changed) return false;
  if (!changed->empty()) {
    const Mdp& mdp = slot_mdp(slot);
    for (EdgeIndex e : *changed) {
      if (!entry.policy.survives_edge_change(e, map_->from_index(e), map_->to_index(e),
                                             mdp.expected_crossing_seconds(e)))
        return false;
    }
  }
  entry.version = now;
  return true;
}

const Policy& TravelPlanner::policy(NodeIndex target, Time depart) {
  check_node(*map_, target);
  const std::int64_t slot = slot_of(depart);
  const auto key = std::make_pair(slot, target);
  auto it = policies_.find(key);
  if (it != policies_.end()) {
    if (refresh(it->second, slot)) {
      ++kept_;
      return it->second.policy;
    }
    ++resolved_;
    policies_.erase(it);
  }
  Policy solved = solve_policy(target, depart);
  if (policies_.size() >= options_.max_cached_policies) policies_.clear();
  return policies_.emplace(key, CachedPolicy{std::move(solved), models_->version()}).first->second.policy;
}

Policy TravelPlanner::solve_policy(NodeIndex target, Time depart) {
  check_node(*map_, target);
  const std::shared_ptr<const Mdp> mdp = slot_entry(slot_of(depart));  // kept alive while solving
  return std::move(solver_.solve(*mdp, target).value().policy);        // target checked above
}

double TravelPlanner::expected_seconds(NodeIndex from, NodeIndex to, Time depart) {
  check_node(*map_, from);
  check_node(*map_, to);
  if (from == to) return 0.0;
  return policy(to, depart).expected_seconds(from);
}

double TravelPlanner::edge_arrival(EdgeIndex edge, Time depart, double t, double* start_out) {
  // Times are seconds after `depart`; slot j spans [s_j, s_{j+1}) with s_j = j w − depart.
  const std::int64_t depart_ms = depart.time_since_epoch().count();
  const std::int64_t w = options_.slot_width.count();
  auto slot_begin = [&](std::int64_t j) { return static_cast<double>(j * w - depart_ms) / 1000.0; };
  const double absolute_ms = static_cast<double>(depart_ms) + t * 1000.0;
  std::int64_t slot = static_cast<std::int64_t>(std::floor(absolute_ms / static_cast<double>(w)));
  // Guard the floating-point floor: t must lie inside slot `slot`.
  if (slot_begin(slot) > t) --slot;
  if (slot_begin(slot + 1) <= t) ++slot;

  // FIFO repair: a(t) = min over t' >= t of t' + c(t'). Inside t's slot the minimum is at t; in a
  // later slot j it is at s_j. Slots starting after the best arrival so far cannot improve it.
  double best = t + slot_mdp(slot).expected_crossing_seconds(edge);
  double start = t;
  const double max_wait = to_seconds(options_.max_wait);
  for (std::int64_t j = slot + 1;; ++j) {
    const double s = slot_begin(j);
    if (!(s < best) || s - t > max_wait) break;
    const double candidate = s + slot_mdp(j).expected_crossing_seconds(edge);
    if (candidate < best) {
      best = candidate;
      start = s;
    }
  }
  if (start_out != nullptr) *start_out = start;
  return best;
}

TravelPlanner::TimedSearch TravelPlanner::time_dependent_search(NodeIndex from, Time depart,
                                                                std::optional<NodeIndex> stop_at) {
  const std::size_t n = map_->node_count();
  TimedSearch search{.arrival = std::vector<double>(n, kInfinity), .via = std::vector<TimedStep>(n),
                     .has_via = std::vector<bool>(n, false)};
  std::vector<bool> done(n, false);
  using Entry = std::pair<double, NodeIndex>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  search.arrival[from] = 0.0;
  queue.emplace(0.0, from);
  // Time-dependent Dijkstra: correct because every repaired edge arrival function is FIFO
  // (non-decreasing) and never earlier than its start time.
  while (!queue.empty()) {
    const auto [t, u] = queue.top();
    queue.pop();
    if (done[u]) continue;
    done[u] = true;
    if (stop_at && u == *stop_at) break;
    for (EdgeIndex e : map_->out_edges(u)) {
      const NodeIndex v = map_->to_index(e);
      if (done[v]) continue;
      double start = t;
      const double a = edge_arrival(e, depart, t, &start);
      if (a < search.arrival[v]) {
        search.arrival[v] = a;
        search.via[v] = {.edge = e, .from = u, .to = v, .reach_seconds = t, .start_seconds = start, .arrive_seconds = a};
        search.has_via[v] = true;
        queue.emplace(a, v);
      }
    }
  }
  return search;
}

TimedRoute TravelPlanner::time_dependent_route(NodeIndex from, NodeIndex to, Time depart) {
  check_node(*map_, from);
  check_node(*map_, to);
  TimedRoute route;
  if (from == to) {
    route.reachable = true;
    route.arrival_seconds = 0.0;
    return route;
  }
  const TimedSearch search = time_dependent_search(from, depart, to);
  if (!(search.arrival[to] < kInfinity)) return route;
  route.reachable = true;
  route.arrival_seconds = search.arrival[to];
  for (NodeIndex at = to; at != from && search.has_via[at]; at = search.via[at].from)
    route.steps.push_back(search.via[at]);
  std::reverse(route.steps.begin(), route.steps.end());
  return route;
}

std::vector<double> TravelPlanner::time_dependent_arrivals(NodeIndex from, Time depart) {
  check_node(*map_, from);
  return time_dependent_search(from, depart, std::nullopt).arrival;
}

}  // namespace rondo::plan
