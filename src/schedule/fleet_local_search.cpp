// Descent on a fleet solution: relocate (each request to its cheapest place anywhere) and, for the
// routing benchmarks' case (static travel, demands only, the distance objective), 2-opt* (two
// routes exchange their tails), tested in O(1) with the stored latest starts and loads.
#include <algorithm>

#include "fleet_search.h"

namespace rondo::schedule::detail {

namespace {

constexpr double kGain = 1e-7;

// Relocates requests while one move gains; true when something moved.
bool relocate_pass(const FleetModel& m, const RouteOps& routes, const SolutionOps& sol, FleetSolution& s) {
  bool moved = false;
  const bool open_robots = !m.hierarchical();
  for (int q = 0; q < static_cast<int>(m.requests().size()); ++q) {
    const int r = s.route_of[m.requests()[q].first];
    if (r < 0) continue;
    const Tour saved = s.routes[r];
    const std::vector<int> saved_unassigned = s.unassigned;
    sol.remove(s, q);
    const Insertion ins = sol.best_insertion(s, q, open_robots);
    if (ins.found() && s.routes[r].cost + ins.delta < saved.cost - kGain) {
      sol.insert(s, ins, q);
      moved = true;
      continue;
    }
    s.routes[r] = saved;
    s.unassigned = saved_unassigned;
    const Request& req = m.requests()[q];
    s.route_of[req.first] = r;
    if (req.drop >= 0) s.route_of[req.drop] = r;
  }
  (void)routes;
  return moved;
}

class TwoOptStar {
 public:
  TwoOptStar(const FleetModel& m, const RouteOps& routes) : m_(m), routes_(routes) {}

  // The first improving tail exchange between routes a and b, applied; true when one was.
  bool improve(FleetSolution& s, int a, int b) const {
    Tour& ra = s.routes[a];
    Tour& rb = s.routes[b];
    const int na = static_cast<int>(ra.seq.size()), nb = static_cast<int>(rb.seq.size());
    for (int i = -1; i < na; ++i)
      for (int j = -1; j < nb; ++j) {
        if ((i == na - 1 && j == nb - 1) || (i == -1 && j == -1)) continue;
        if (!fits(ra, i, rb, j) || !fits(rb, j, ra, i)) continue;
        const double gain = arc(ra, i) + arc(rb, j) - cross(ra, i, rb, j) - cross(rb, j, ra, i) +
                            vehicle_change(na, i, nb, j);
        if (gain <= kGain) continue;
        std::vector<int> new_a(ra.seq.begin(), ra.seq.begin() + (i + 1));
        new_a.insert(new_a.end(), rb.seq.begin() + (j + 1), rb.seq.end());
        std::vector<int> new_b(rb.seq.begin(), rb.seq.begin() + (j + 1));
        new_b.insert(new_b.end(), ra.seq.begin() + (i + 1), ra.seq.end());
        ra.seq = std::move(new_a);
        rb.seq = std::move(new_b);
        routes_.update(ra);
        routes_.update(rb);
        for (int x : ra.seq) s.route_of[x] = a;
        for (int x : rb.seq) s.route_of[x] = b;
        return true;
      }
    return false;
  }

 private:
  std::size_t here(const Tour& r, int i) const {
    return i < 0 ? m_.robot_start(r.robot) : m_.end_location(r.seq[i]);
  }
  // Distance from position i to what follows it (the next task, the dock, or nothing).
  double arc(const Tour& r, int i) const {
    const int n = static_cast<int>(r.seq.size());
    if (i + 1 < n) return m_.distance(here(r, i), m_.start_location(r.seq[i + 1]));
    return m_.has_end(r.robot) ? m_.distance(here(r, i), m_.robot_end(r.robot)) : 0.0;
  }
  // Distance from position i of `head` to the tail of `tail` after j.
  double cross(const Tour& head, int i, const Tour& tail, int j) const {
    const int n = static_cast<int>(tail.seq.size());
    if (j + 1 < n) return m_.distance(here(head, i), m_.start_location(tail.seq[j + 1]));
    if (i < 0) return 0.0;  // the head's robot ends up unused
    return m_.has_end(head.robot) ? m_.distance(here(head, i), m_.robot_end(head.robot)) : 0.0;
  }
  double vehicle_change(int na, int i, int nb, int j) const {
    double gain = 0;
    if (i < 0 && j + 1 >= nb) gain += kVehicleCost;  // a ends empty
    if (j < 0 && i + 1 >= na) gain += kVehicleCost;  // b ends empty
    return gain;
  }
  // Can head's robot run head[0..i] then tail[j+1..]?
  bool fits(const Tour& head, int i, const Tour& tail, int j) const {
    const int n = static_cast<int>(tail.seq.size());
    const std::int64_t t = i < 0 ? m_.free_from(head.robot) : head.end[i];
    const std::int64_t load = head.load_before[i + 1] + (tail.load_before[n] - tail.load_before[j + 1]);
    if (load > m_.capacity(head.robot)) return false;
    // Each task of the tail must be one head's robot may do (pins, actions).
    for (int k = j + 1; k < n; ++k)
      if (!m_.allowed(head.robot, tail.seq[k])) return false;
    if (j + 1 >= n) {
      if (i < 0 || !m_.has_end(head.robot)) return true;
      return t + m_.travel(head.robot, here(head, i), m_.robot_end(head.robot), t) <= m_.end_latest(head.robot);
    }
    const int x = tail.seq[j + 1];
    const std::int64_t s = std::max(t + m_.travel(head.robot, here(head, i), m_.start_location(x), t), m_.release(x));
    return s <= tail.latest[j + 1];
  }

  const FleetModel& m_;
  const RouteOps& routes_;
};

}  // namespace

void FleetSearch::descend(FleetSolution& s) {
  if (!options_.improve) return;
  const bool tails = m_.simple() && m_.hierarchical();
  const TwoOptStar two_opt(m_, routes_);
  for (int pass = 0; pass < 10 && !stopped(); ++pass) {
    bool moved = relocate_pass(m_, routes_, sol_, s);
    if (tails)
      for (int a = 0; a < static_cast<int>(s.routes.size()); ++a)
        for (int b = a + 1; b < static_cast<int>(s.routes.size()); ++b) {
          if (s.routes[a].empty() || s.routes[b].empty() || !m_.same_ends(s.routes[a].robot, s.routes[b].robot)) continue;
          while (!stopped() && two_opt.improve(s, a, b)) moved = true;
        }
    if (!moved) break;
  }
  s.cost = sol_.cost(s);
}

}  // namespace rondo::schedule::detail
