#include "fleet_solution.h"

#include <algorithm>

namespace rondo::schedule::detail {

FleetSolution SolutionOps::empty_solution() const {
  FleetSolution s;
  s.routes.resize(m_.robots());
  for (int r = 0; r < m_.robots(); ++r) {
    s.routes[r].robot = r;
    ops_.update(s.routes[r]);
  }
  s.route_of.assign(m_.tasks(), -1);
  for (int q = 0; q < static_cast<int>(m_.requests().size()); ++q) s.unassigned.push_back(q);
  s.cost = cost(s);
  return s;
}

FleetSolution SolutionOps::from_orders(const std::vector<std::vector<int>>& orders) const {
  FleetSolution s = empty_solution();
  std::vector<bool> placed(m_.requests().size(), false);
  for (int r = 0; r < m_.robots() && r < static_cast<int>(orders.size()); ++r) {
    s.routes[r].seq = orders[r];
    for (int x : orders[r]) {
      s.route_of[x] = r;
      placed[m_.request_of(x)] = true;
    }
    ops_.update(s.routes[r]);
  }
  std::erase_if(s.unassigned, [&](int q) { return placed[q]; });
  s.cost = cost(s);
  return s;
}

double SolutionOps::drop_cost(int q) const {
  const Request& req = m_.requests()[q];
  return m_.drop_cost(req.first) + (req.drop >= 0 ? m_.drop_cost(req.drop) : 0.0);
}

double SolutionOps::cost(const FleetSolution& s) const {
  double c = 0;
  for (const Tour& r : s.routes) c += r.cost;
  for (int q : s.unassigned) c += drop_cost(q);
  if (m_.has_after())
    for (int i = 0; i < m_.tasks(); ++i) {
      if (s.route_of[i] < 0) continue;
      for (int p : m_.predecessors(i))
        if (s.route_of[p] < 0) {
          c += m_.drop_cost(i);  // it will be dropped with its predecessor
          break;
        }
    }
  return c;
}

void SolutionOps::insert(FleetSolution& s, const Insertion& ins, int q) const {
  Tour& r = s.routes[ins.route];
  if (r.empty() && s.open_budget > 0) --s.open_budget;
  ops_.insert(r, ins, q);
  const Request& req = m_.requests()[q];
  s.route_of[req.first] = ins.route;
  if (req.drop >= 0) s.route_of[req.drop] = ins.route;
  std::erase(s.unassigned, q);
}

void SolutionOps::remove(FleetSolution& s, int q) const {
  const Request& req = m_.requests()[q];
  const int r = s.route_of[req.first];
  if (r < 0) return;
  ops_.remove(s.routes[r], q);
  s.route_of[req.first] = -1;
  if (req.drop >= 0) s.route_of[req.drop] = -1;
  s.unassigned.push_back(q);
}

Insertion SolutionOps::best_insertion(const FleetSolution& s, int q, bool allow_empty, double blink,
                                      std::mt19937_64* rng) const {
  Insertion best;
  double open_cost = m_.hierarchical() ? kVehicleCost : 0.0;
  if (m_.hierarchical() && s.open_budget > 0) {
    allow_empty = true;
    open_cost = 0;
  }
  std::vector<char> tried_kind;  // empty robots of one kind give the same answer: try one
  if (allow_empty) tried_kind.assign(s.routes.size(), 0);
  for (int r = 0; r < static_cast<int>(s.routes.size()); ++r) {
    const Tour& route = s.routes[r];
    if (!s.focus.empty() && !s.focus[r]) continue;
    if (route.empty()) {
      if (!allow_empty || tried_kind[m_.kind(r)]) continue;
      tried_kind[m_.kind(r)] = 1;
    }
    const Insertion ins = ops_.best_insertion(route, r, q, s.route_of, allow_empty, open_cost, blink, rng);
    if (ins.delta < best.delta) best = ins;
  }
  return best;
}

}  // namespace rondo::schedule::detail
