#include "fleet_route.h"

#include <algorithm>

namespace rondo::schedule::detail {

void RouteOps::update(Tour& r) const {
  const std::size_t n = r.seq.size();
  r.start.resize(n);
  r.end.resize(n);
  r.load_before.resize(n + 1);
  r.max_load_from.assign(n + 1, -kFleetNever);
  r.latest.resize(n);
  r.wait_sum.resize(n);
  r.wait_sum_sum.assign(n + 1, 0);
  std::int64_t t = m_.free_from(r.robot);
  std::size_t loc = m_.robot_start(r.robot);
  std::int64_t load = 0;
  double sum = 0;
  r.distance = 0;
  r.feasible = true;
  for (std::size_t k = 0; k < n; ++k) {
    const int x = r.seq[k];
    r.load_before[k] = load;
    const std::int64_t arrival = t + m_.travel(r.robot, loc, m_.start_location(x), t);
    const std::int64_t s = std::max(arrival, m_.release(x));
    if (s > m_.latest(x)) r.feasible = false;
    r.wait_sum[k] = (k > 0 ? r.wait_sum[k - 1] : 0) + (s - arrival);
    r.wait_sum_sum[k + 1] = r.wait_sum_sum[k] + r.wait_sum[k];
    r.start[k] = s;
    r.end[k] = s + m_.duration(x);
    r.distance += m_.distance(loc, m_.start_location(x));
    sum += static_cast<double>(r.end[k] - m_.free_from(r.robot)) / 1000.0 + m_.lateness_cost(x, r.end[k]);
    load += m_.load(x);
    if (load > m_.capacity(r.robot)) r.feasible = false;
    t = r.end[k];
    loc = m_.end_location(x);
  }
  r.load_before[n] = load;
  if (n > 0 && m_.has_end(r.robot)) {
    r.distance += m_.distance(loc, m_.robot_end(r.robot));
    if (t + dock_travel(r, loc, t) > m_.end_latest(r.robot)) r.feasible = false;
  }
  for (std::size_t k = n; k-- > 0;)
    r.max_load_from[k] = std::max(r.max_load_from[k + 1], r.load_before[k] + m_.load(r.seq[k]));
  if (m_.static_travel() && n > 0) {
    const int last = r.seq[n - 1];
    std::int64_t bound = m_.latest(last);
    if (m_.has_end(r.robot))
      bound = std::min(bound, m_.end_latest(r.robot) - m_.duration(last) - dock_travel(r, m_.end_location(last), 0));
    r.latest[n - 1] = bound;
    for (std::size_t k = n - 1; k-- > 0;) {
      const int x = r.seq[k];
      const int y = r.seq[k + 1];
      r.latest[k] = std::min(m_.latest(x), r.latest[k + 1] - m_.travel(r.robot, m_.end_location(x), m_.start_location(y), 0) -
                                               m_.duration(x));
    }
  }
  r.cost = m_.hierarchical() ? r.distance + (n > 0 ? kVehicleCost : 0.0) : sum;
}

std::int64_t RouteOps::dock_travel(const Tour& r, std::size_t from, std::int64_t depart) const {
  return m_.travel(r.robot, from, m_.robot_end(r.robot), depart);
}

std::size_t RouteOps::prev_location(const Tour& r, int pos) const {
  return pos == 0 ? m_.robot_start(r.robot) : m_.end_location(r.seq[pos - 1]);
}

RouteOps::Walk RouteOps::walk_at(const Tour& r, int pos) const {
  Walk w;
  w.t = pos == 0 ? m_.free_from(r.robot) : r.end[pos - 1];
  w.loc = prev_location(r, pos);
  w.load = r.load_before[pos];
  return w;
}

bool RouteOps::step_new(const Tour& r, int task, Walk& w) const {
  const std::int64_t s = std::max(w.t + m_.travel(r.robot, w.loc, m_.start_location(task), w.t), m_.release(task));
  if (s > m_.latest(task)) return false;
  const std::int64_t e = s + m_.duration(task);
  w.load += m_.load(task);
  if (w.load > m_.capacity(r.robot)) return false;
  if (!m_.hierarchical())
    w.delta += static_cast<double>(e - m_.free_from(r.robot)) / 1000.0 + m_.lateness_cost(task, e);
  w.start = s;
  w.t = e;
  w.loc = m_.end_location(task);
  return true;
}

bool RouteOps::step_old(const Tour& r, int k, std::int64_t extra_load, Walk& w) const {
  const int x = r.seq[k];
  const std::int64_t s = std::max(w.t + m_.travel(r.robot, w.loc, m_.start_location(x), w.t), m_.release(x));
  if (s > m_.latest(x)) return false;
  const std::int64_t e = s + m_.duration(x);
  w.load = r.load_before[k] + m_.load(x) + extra_load;
  if (w.load > m_.capacity(r.robot)) return false;
  if (!m_.hierarchical())
    w.delta += static_cast<double>(e - r.end[k]) / 1000.0 + m_.lateness_cost(x, e) - m_.lateness_cost(x, r.end[k]);
  w.start = s;
  w.t = e;
  w.loc = m_.end_location(x);
  return true;
}

// From position k on (after the inserted tasks): feasible, and the change of the sum of ends.
bool RouteOps::finish(const Tour& r, int k, std::int64_t extra_load, Walk w, double& delta) const {
  const int n = static_cast<int>(r.seq.size());
  const bool load_ok_rest = [&] { return extra_load <= 0; }();
  for (; k < n; ++k) {
    const int x = r.seq[k];
    const std::int64_t s = std::max(w.t + m_.travel(r.robot, w.loc, m_.start_location(x), w.t), m_.release(x));
    const bool rest_fits = load_ok_rest || r.max_load_from[k] + extra_load <= m_.capacity(r.robot);
    if (s == r.start[k]) {
      delta = w.delta;
      return rest_fits;
    }
    if (m_.static_travel()) {
      if (s > r.latest[k] || !rest_fits) return false;
      if (m_.hierarchical()) {
        delta = w.delta;
        return true;
      }
      if (s > r.start[k] && !m_.has_due()) {
        delta = w.delta + shifted_ends(r, k, s - r.start[k]);
        return true;
      }
    }
    if (!step_old(r, k, extra_load, w)) return false;
  }
  if (m_.has_end(r.robot) && w.t + dock_travel(r, w.loc, w.t) > m_.end_latest(r.robot)) return false;
  delta = w.delta;
  return true;
}

// The change of the sum of ends (seconds) when start k moves later by `delay`: every later start
// moves by what the waiting before it has not absorbed (static travel).
double RouteOps::shifted_ends(const Tour& r, int k, std::int64_t delay) const {
  const auto& p = r.wait_sum;
  // The last position j >= k that the delay still reaches: p[j] - p[k] < delay.
  const auto last = std::lower_bound(p.begin() + k, p.end(), p[k] + delay) - p.begin() - 1;
  const std::int64_t count = last - k + 1;
  const std::int64_t moved = count * (delay + p[k]) - (r.wait_sum_sum[last + 1] - r.wait_sum_sum[k]);
  return static_cast<double>(moved) / 1000.0;
}

double RouteOps::single_distance(const Tour& r, int pos, int task) const {
  const int n = static_cast<int>(r.seq.size());
  const std::size_t prev = prev_location(r, pos);
  double d = m_.distance(prev, m_.start_location(task));
  if (pos < n || m_.has_end(r.robot)) {
    const std::size_t next = pos < n ? m_.start_location(r.seq[pos]) : m_.robot_end(r.robot);
    d += m_.distance(m_.end_location(task), next) - m_.distance(prev, next);
  }
  return d;
}

double RouteOps::pair_distance(const Tour& r, int pos, int drop_pos, int a, int b) const {
  if (drop_pos > pos) return single_distance(r, pos, a) + single_distance(r, drop_pos, b);
  const int n = static_cast<int>(r.seq.size());
  const std::size_t prev = prev_location(r, pos);
  double d = m_.distance(prev, m_.start_location(a)) + m_.distance(m_.end_location(a), m_.start_location(b));
  if (pos < n || m_.has_end(r.robot)) {
    const std::size_t next = pos < n ? m_.start_location(r.seq[pos]) : m_.robot_end(r.robot);
    d += m_.distance(m_.end_location(b), next) - m_.distance(prev, next);
  }
  return d;
}

// No item of this look on board when arriving at `pos`.
bool RouteOps::looks_clear(const Tour& r, int pos, int, int look) const {
  int on_board = 0;
  for (int k = 0; k < pos; ++k)
    if (m_.look(r.seq[k]) == look) on_board += m_.load(r.seq[k]) > 0 ? 1 : -1;
  return on_board <= 0;
}

// Positions [lo, hi] where `task` may go given its `after` links; lo > hi when none.
std::pair<int, int> RouteOps::allowed_range(const Tour& r, int task, const std::vector<int>& route_of, int index) const {
  int lo = 0, hi = static_cast<int>(r.seq.size());
  auto position = [&](int x) {
    return static_cast<int>(std::find(r.seq.begin(), r.seq.end(), x) - r.seq.begin());
  };
  for (int p : m_.predecessors(task)) {
    if (route_of[p] < 0) continue;
    if (route_of[p] != index) return {1, 0};
    lo = std::max(lo, position(p) + 1);
  }
  for (int s : m_.successors(task)) {
    if (route_of[s] < 0) continue;
    if (route_of[s] != index) return {1, 0};
    hi = std::min(hi, position(s));
  }
  return {lo, hi};
}

Insertion RouteOps::best_insertion(const Tour& r, int index, int q, const std::vector<int>& route_of, bool allow_empty,
                                   double open_cost, double blink, std::mt19937_64* rng) const {
  Insertion best;
  if (!allow_empty && r.empty()) return best;
  const Request& req = m_.requests()[q];
  const int a = req.first, b = req.drop;
  if (!m_.allowed(r.robot, a) || (b >= 0 && !m_.allowed(r.robot, b))) return best;
  const int n = static_cast<int>(r.seq.size());
  auto [lo, hi] = m_.has_after() ? allowed_range(r, a, route_of, index) : std::pair<int, int>{0, n};
  auto [blo, bhi] = b >= 0 && m_.has_after() ? allowed_range(r, b, route_of, index) : std::pair<int, int>{0, n};
  // Only positions in the task's window can hold it: after a task that ends past its latest start
  // nothing fits (ends only grow along a route), and (one task, static travel) before a task whose
  // latest start comes before this one could even end, nothing fits either (latest starts grow too).
  hi = std::min(hi, static_cast<int>(std::upper_bound(r.end.begin(), r.end.end(), m_.latest(a)) - r.end.begin()));
  if (b < 0 && m_.static_travel()) {
    const std::int64_t earliest_end = m_.release(a) + m_.duration(a);
    lo = std::max(lo, static_cast<int>(std::lower_bound(r.latest.begin(), r.latest.end(), earliest_end) - r.latest.begin()));
  }
  const double vehicle = m_.hierarchical() && r.empty() ? open_cost : 0.0;
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  auto skip = [&] { return blink > 0 && rng && coin(*rng) < blink; };
  for (int pos = lo; pos <= hi; ++pos) {
    if (b < 0) {
      const double dd = m_.hierarchical() ? single_distance(r, pos, a) + vehicle : 0;
      if (m_.hierarchical() && dd >= best.delta) continue;
      if (skip()) continue;
      Walk w = walk_at(r, pos);
      double d = 0;
      if (!step_new(r, a, w) || !finish(r, pos, m_.load(a), w, d)) continue;
      const double delta = m_.hierarchical() ? dd : d;
      if (delta < best.delta) best = {delta, index, pos, -1};
      continue;
    }
    Walk run = walk_at(r, pos);
    if (!step_new(r, a, run)) continue;
    const int look = m_.look(a);
    if (look >= 0 && !looks_clear(r, pos, pos, look)) continue;
    for (int j = pos; j <= std::min(n, bhi); ++j) {
      if (j > pos) {
        const int x = r.seq[j - 1];
        if (look >= 0 && m_.look(x) == look && m_.load(x) > 0) break;
        if (!step_old(r, j - 1, m_.load(a), run)) break;
        if (m_.static_travel() && run.start > r.latest[j - 1]) break;
      }
      if (j < blo) continue;
      const double dd = m_.hierarchical() ? pair_distance(r, pos, j, a, b) + vehicle : 0;
      if (m_.hierarchical() && dd >= best.delta) continue;
      if (skip()) continue;
      Walk w = run;
      double d = 0;
      if (!step_new(r, b, w) || !finish(r, j, 0, w, d)) continue;
      const double delta = m_.hierarchical() ? dd : d;
      if (delta < best.delta) best = {delta, index, pos, j};
    }
  }
  return best;
}

void RouteOps::insert(Tour& r, const Insertion& ins, int q) const {
  const Request& req = m_.requests()[q];
  if (req.drop >= 0) r.seq.insert(r.seq.begin() + ins.drop_pos, req.drop);
  r.seq.insert(r.seq.begin() + ins.pos, req.first);
  update(r);
}

void RouteOps::remove(Tour& r, int q) const {
  const Request& req = m_.requests()[q];
  std::erase_if(r.seq, [&](int x) { return x == req.first || x == req.drop; });
  update(r);
}

}  // namespace rondo::schedule::detail
