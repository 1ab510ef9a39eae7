// Putting requests into routes: regret-2 (cached per request and route), greedy with blinks, and
// the choice between them for the search's recreate step.
#include <algorithm>
#include <limits>

#include "fleet_search.h"

namespace rondo::schedule::detail {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Empty robots: the first empty one of each kind stands for its kind.
std::vector<int> empty_representatives(const FleetModel& m, const FleetSolution& s) {
  std::vector<int> rep(s.routes.size(), -1);
  std::vector<int> out;
  for (int r = 0; r < static_cast<int>(s.routes.size()); ++r)
    if (s.routes[r].empty() && rep[m.kind(r)] < 0) {
      rep[m.kind(r)] = r;
      out.push_back(r);
    }
  return out;
}

}  // namespace

// Regret-2 recomputes every request's insertion into the route that changed: quadratic in the
// tasks. Past kRegretWork (requests x robots), the requests go in one by one instead, tightest
// latest start first, each to its cheapest place: the first plan of a large fleet in well under
// a second, for the search to improve.
constexpr std::size_t kRegretWork = 50000;

void FleetSearch::construct(FleetSolution& s) {
  if (m_.requests().size() * static_cast<std::size_t>(m_.robots()) <= kRegretWork) {
    regret(s, s.unassigned, true);
  } else {
    std::vector<int> order = s.unassigned;
    const auto& req = m_.requests();
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return m_.latest(req[a].first) < m_.latest(req[b].first); });
    for (int q : order) {
      if (stopped()) break;
      const Insertion ins = sol_.best_insertion(s, q, true);
      if (ins.found()) sol_.insert(s, ins, q);
    }
  }
  s.cost = sol_.cost(s);
  report(s, 0);
}

void FleetSearch::regret(FleetSolution& s, std::vector<int> pending, bool allow_empty) {
  const int routes = static_cast<int>(s.routes.size());
  // cache[i * routes + r]: best insertion of pending[i] into route r (empty routes: only their
  // kind's representative is filled).
  std::vector<Insertion> cache(pending.size() * routes);
  auto fill_route = [&](int r) {
    const Tour& route = s.routes[r];
    for (std::size_t i = 0; i < pending.size(); ++i)
      cache[i * routes + r] = pending[i] < 0 ? Insertion{}
                                             : routes_.best_insertion(route, r, pending[i], s.route_of, allow_empty,
                                                                      m_.hierarchical() ? kVehicleCost : 0.0);
  };
  auto fill_all = [&] {
    std::fill(cache.begin(), cache.end(), Insertion{});
    for (int r = 0; r < routes; ++r)
      if (!s.routes[r].empty()) fill_route(r);
    if (allow_empty)
      for (int r : empty_representatives(m_, s)) fill_route(r);
  };
  fill_all();
  for (std::size_t left = pending.size(); left > 0; --left) {
    if (stopped()) return;
    int pick = -1;
    double pick_regret = -1, pick_best = kInf;
    for (std::size_t i = 0; i < pending.size(); ++i) {
      if (pending[i] < 0) continue;
      double b1 = kInf, b2 = kInf;
      for (int r = 0; r < routes; ++r) {
        const double d = cache[i * routes + r].delta;
        if (d < b1) {
          b2 = b1;
          b1 = d;
        } else if (d < b2) {
          b2 = d;
        }
      }
      if (b1 == kInf) continue;
      const double reg = b2 == kInf ? std::numeric_limits<double>::max() : b2 - b1;
      if (reg > pick_regret || (reg == pick_regret && b1 < pick_best)) {
        pick = static_cast<int>(i);
        pick_regret = reg;
        pick_best = b1;
      }
    }
    if (pick < 0) return;  // the rest fit nowhere
    Insertion ins;
    for (int r = 0; r < routes; ++r)
      if (cache[pick * routes + r].delta < ins.delta) ins = cache[pick * routes + r];
    const bool was_empty = s.routes[ins.route].empty();
    sol_.insert(s, ins, pending[pick]);
    pending[pick] = -1;
    cache[pick * routes + ins.route] = Insertion{};
    if (m_.has_after()) {
      fill_all();
      continue;
    }
    fill_route(ins.route);
    if (was_empty && allow_empty) {
      // Its kind is now stood for by the next empty robot of that kind, if any.
      for (int r : empty_representatives(m_, s))
        if (m_.kind(r) == m_.kind(ins.route)) fill_route(r);
    }
  }
}

void FleetSearch::greedy(FleetSolution& s, std::vector<int> order, bool allow_empty, double blink) {
  for (int q : order) {
    const Insertion ins = sol_.best_insertion(s, q, allow_empty, blink, &rng_);
    if (ins.found()) sol_.insert(s, ins, q);
  }
}

void FleetSearch::recreate(FleetSolution& s, bool allow_empty) {
  std::vector<int> order = s.unassigned;
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  const double pick = coin(rng_);
  if (pick < 0.2) {
    regret(s, order, allow_empty);
  } else {
    std::shuffle(order.begin(), order.end(), rng_);
    auto key_sort = [&](auto key) {
      std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return key(a) > key(b); });
    };
    const auto& req = m_.requests();
    if (pick < 0.45) {
      key_sort([&](int q) { return m_.load(req[q].first); });  // biggest demand first
    } else if (pick < 0.65) {
      key_sort([&](int q) {  // farthest from its robots' starts first
        return m_.distance(m_.robot_start(0), m_.start_location(req[q].first));
      });
    } else if (pick < 0.8) {
      key_sort([&](int q) { return -static_cast<double>(m_.latest(req[q].first) - m_.release(req[q].first)); });
    }
    greedy(s, order, allow_empty, 0.01);
  }
  if (!allow_empty && !s.unassigned.empty()) greedy(s, s.unassigned, true, 0.0);
  s.cost = sol_.cost(s);
}

}  // namespace rondo::schedule::detail
