// The fleet solver's improvement loop: route minimisation for the hierarchical objective, then
// simulated annealing over ruin and recreate. Every decision comes from the seeded generator and
// the iteration count, never from a clock; `stop` is polled once per iteration.
#include "fleet_search.h"

#include <algorithm>
#include <cmath>

namespace rondo::schedule::detail {

namespace {

// Pool weight of a request left out while emptying a route: above any distance change.
constexpr double kPoolWeight = 1e4;

}  // namespace

FleetSearch::FleetSearch(const FleetModel& model, const FleetSchedulerOptions& options, const StopCondition& stop)
    : m_(model), options_(options), stop_(stop), routes_(model), sol_(model, routes_), rng_(options.seed) {}

bool FleetSearch::stopped() {
  if (!stopped_) stopped_ = stop_.should_stop();
  return stopped_;
}

void FleetSearch::report(const FleetSolution& s, std::size_t iteration) const {
  if (!options_.on_progress) return;
  FleetProgress p{.vehicles = static_cast<std::size_t>(s.vehicles()), .objective = s.cost,
                  .unplanned = s.unassigned.size(), .iteration = iteration};
  for (const Tour& r : s.routes) p.distance += r.distance;
  options_.on_progress(p);
}

FleetSolution FleetSearch::improve(FleetSolution s) {
  descend(s);
  if (m_.hierarchical()) minimise_all_routes(s);
  anneal(s);
  return s;
}

// Empties the smallest route while an attempt succeeds.
void FleetSearch::minimise_all_routes(FleetSolution& best) {
  while (!stopped() && minimise_routes(best, 0)) {
  }
}

// Empties the smallest route into a pool and searches, with the routes fixed in number, until the
// pool is placed (true: `best` has one robot fewer) or the attempt's iterations run out.
// Fewer robots than this cannot carry the demands (robots' capacities, largest first).
int FleetSearch::vehicle_lower_bound() const {
  std::int64_t demand = 0;
  for (int i = 0; i < m_.tasks(); ++i) demand += std::max<std::int64_t>(0, m_.problem().tasks[i].demand);
  std::vector<std::int64_t> capacity;
  for (int r = 0; r < m_.robots(); ++r) capacity.push_back(m_.capacity(r));
  std::sort(capacity.rbegin(), capacity.rend());
  int k = 1;
  for (std::int64_t carried = capacity.empty() ? 0 : capacity[0]; carried < demand && k < m_.robots(); ++k)
    carried += capacity[k];
  return k;
}

bool FleetSearch::minimise_routes(FleetSolution& best, int rank) {
  if (best.vehicles() <= vehicle_lower_bound() || !best.unassigned.empty()) return false;
  FleetSolution current = best;
  // The rank-th smallest route (by tasks, then by index).
  std::vector<int> used;
  for (int r = 0; r < static_cast<int>(current.routes.size()); ++r)
    if (!current.routes[r].empty()) used.push_back(r);
  std::stable_sort(used.begin(), used.end(),
                   [&](int a, int b) { return current.routes[a].seq.size() < current.routes[b].seq.size(); });
  const int smallest = used[std::min<std::size_t>(static_cast<std::size_t>(rank), used.size() - 1)];
  const std::vector<int> seq = current.routes[smallest].seq;
  for (int x : seq)
    if (current.route_of[x] >= 0) sol_.remove(current, m_.request_of(x));
  std::vector<double> weight(m_.requests().size(), 1.0);
  auto pool_cost = [&](const FleetSolution& s) {
    double c = 0;
    for (const Tour& r : s.routes) c += r.cost;
    for (int q : s.unassigned) c += kPoolWeight * weight[q];
    return c;
  };
  greedy(current, current.unassigned, false, 0.0);
  std::uniform_real_distribution<double> coin(1e-12, 1.0);
  // An attempt is bounded by the problem's size too, so that small problems keep most of a poll
  // budget for the annealing.
  const std::size_t attempt = std::min(options_.route_min_iterations, 200 * m_.requests().size());
  for (std::size_t it = 0; it < attempt; ++it) {
    current.open_budget = 0;
    if (current.unassigned.empty()) {
      current.cost = sol_.cost(current);
      best = current;
      descend(best);
      report(best, it);
      return true;
    }
    if (stopped()) return false;
    FleetSolution cand = current;
    // Half the time, make room around a request of the pool.
    if (coin(rng_) < 0.5) {
      const int seed = current.unassigned[std::uniform_int_distribution<std::size_t>(0, current.unassigned.size() - 1)(rng_)];
      ruin_related(cand, removal_count(), seed);
    } else {
      ruin(cand);
    }
    cand.open_budget = current.vehicles() - cand.vehicles();
    std::vector<int> order = cand.unassigned;
    std::shuffle(order.begin(), order.end(), rng_);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return weight[a] > weight[b]; });
    greedy(cand, order, false, 0.01);
    for (int q : cand.unassigned) weight[q] += 1;
    if (pool_cost(cand) <= pool_cost(current)) current = std::move(cand);
  }
  return false;
}

void FleetSearch::anneal(FleetSolution& best) {
  if (!options_.improve) return;
  FleetSolution current = best;
  // The temperature's scale: the objective per planned request (distance per customer, or the
  // time from the robot's start to the end of its route per task).
  auto scale = [&](const FleetSolution& s) {
    double total = 0;
    int planned = 0;
    for (const Tour& r : s.routes) {
      if (r.empty()) continue;
      planned += static_cast<int>(r.seq.size());
      total += m_.hierarchical() ? r.distance : static_cast<double>(r.end.back() - m_.free_from(r.robot)) / 1000.0;
    }
    return planned > 0 ? total / planned : 1.0;
  };
  const double unit = std::max(1e-6, scale(best));
  const bool open_robots = !m_.hierarchical();
  std::uniform_real_distribution<double> coin(1e-12, 1.0);
  const std::size_t cycle = std::max<std::size_t>(1, options_.cycle_iterations);
  for (std::size_t it = 0; !stopped(); ++it) {
    const std::size_t round = it / cycle;
    const double progress = static_cast<double>(it % cycle) / static_cast<double>(cycle);
    const double t_start = 10.0 * unit / static_cast<double>(1 + round);
    const double t_end = 0.1 * unit / static_cast<double>(1 + round);
    const double temperature = t_start * std::pow(t_end / t_start, progress);
    if (it % cycle == 0 && it > 0) current = best;
    FleetSolution cand = current;
    ruin(cand);
    cand.open_budget = current.vehicles() - cand.vehicles();
    recreate(cand, open_robots);
    cand.open_budget = 0;
    if (cand.cost < best.cost - 1e-9) {
      descend(cand);
      best = cand;
      current = cand;
      report(best, it);
      continue;
    }
    if (cand.cost < current.cost - temperature * std::log(coin(rng_))) current = std::move(cand);
    // Every fourth cycle, one more attempt at emptying a route, from the best.
    if (m_.hierarchical() && options_.route_min_iterations > 0 && it % (4 * cycle) == 4 * cycle - 1 &&
        minimise_routes(best, 0)) {
      minimise_all_routes(best);
      current = best;
    }
  }
}

FleetSolution FleetSearch::repair_around(FleetSolution s, int request, std::size_t iterations) {
  const bool open_robots = !m_.hierarchical();
  for (std::size_t it = 0; it < iterations && !stopped(); ++it) {
    FleetSolution cand = s;
    ruin_related(cand, std::min(8, removal_count()), request);
    cand.open_budget = s.vehicles() - cand.vehicles();
    // Reinsert into the routes the ruin touched first (and the new request's), then anywhere.
    cand.focus.assign(cand.routes.size(), 0);
    for (std::size_t r = 0; r < cand.routes.size(); ++r)
      cand.focus[r] = cand.routes[r].seq.size() != s.routes[r].seq.size() ? 1 : 0;
    const int home = s.route_of[m_.requests()[request].first];
    if (home >= 0) cand.focus[home] = 1;
    greedy(cand, cand.unassigned, open_robots, 0.0);
    cand.focus.clear();
    recreate(cand, open_robots);
    cand.open_budget = 0;
    if (cand.cost < s.cost - 1e-9) s = std::move(cand);
  }
  return s;
}

}  // namespace rondo::schedule::detail
