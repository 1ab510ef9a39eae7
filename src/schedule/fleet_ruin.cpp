// Taking requests out of a solution: at random, related to a seed (nearest first, with Ropke and
// Pisinger's randomised rank), strings of consecutive tasks in the routes near a seed (after
// Christiaens and Vanden Berghe's SISR), or a whole small route.
#include <algorithm>
#include <cmath>

#include "fleet_search.h"

namespace rondo::schedule::detail {

namespace {

std::vector<int> assigned_requests(const FleetModel& m, const FleetSolution& s) {
  std::vector<int> out;
  for (int q = 0; q < static_cast<int>(m.requests().size()); ++q)
    if (s.route_of[m.requests()[q].first] >= 0) out.push_back(q);
  return out;
}

}  // namespace

int FleetSearch::removal_count() {
  const int q = static_cast<int>(m_.requests().size());
  const int hi = std::max(1, std::min({q, 40, std::max(4, q * 15 / 100)}));
  const int lo = std::min(hi, 4);
  return std::uniform_int_distribution<int>(lo, hi)(rng_);
}

void FleetSearch::ruin(FleetSolution& s) {
  const double pick = std::uniform_real_distribution<double>(0.0, 1.0)(rng_);
  if (pick < 0.45) ruin_strings(s, removal_count());
  else if (pick < 0.75) ruin_related(s, removal_count());
  else if (pick < 0.93) ruin_random(s, removal_count());
  else ruin_route(s);
}

void FleetSearch::ruin_random(FleetSolution& s, int count) {
  std::vector<int> in = assigned_requests(m_, s);
  std::shuffle(in.begin(), in.end(), rng_);
  for (int k = 0; k < count && k < static_cast<int>(in.size()); ++k) sol_.remove(s, in[k]);
}

void FleetSearch::ruin_related(FleetSolution& s, int count, int seed_request) {
  std::vector<int> in = assigned_requests(m_, s);
  if (seed_request < 0) {
    if (in.empty()) return;
    seed_request = in[std::uniform_int_distribution<std::size_t>(0, in.size() - 1)(rng_)];
  }
  if (s.route_of[m_.requests()[seed_request].first] >= 0) sol_.remove(s, seed_request);
  std::vector<int> removed{seed_request};
  std::uniform_real_distribution<double> coin(0.0, 1.0);
  std::vector<int> candidates;
  while (static_cast<int>(removed.size()) < count) {
    const int from = removed[std::uniform_int_distribution<std::size_t>(0, removed.size() - 1)(rng_)];
    candidates.clear();
    for (int q : m_.neighbours(from))
      if (s.route_of[m_.requests()[q].first] >= 0) candidates.push_back(q);
    if (candidates.empty()) break;
    const auto at = static_cast<std::size_t>(std::pow(coin(rng_), 6.0) * static_cast<double>(candidates.size()));
    const int q = candidates[std::min(at, candidates.size() - 1)];
    sol_.remove(s, q);
    removed.push_back(q);
  }
}

void FleetSearch::ruin_strings(FleetSolution& s, int count) {
  std::vector<int> in = assigned_requests(m_, s);
  if (in.empty()) return;
  const int seed = in[std::uniform_int_distribution<std::size_t>(0, in.size() - 1)(rng_)];
  std::vector<int> near{seed};
  near.insert(near.end(), m_.neighbours(seed).begin(), m_.neighbours(seed).end());
  std::vector<char> route_done(s.routes.size(), 0);
  int removed = 0;
  for (int q : near) {
    if (removed >= count) break;
    const int r = s.route_of[m_.requests()[q].first];
    if (r < 0 || route_done[r]) continue;
    route_done[r] = 1;
    const std::vector<int> seq = s.routes[r].seq;
    const int len = static_cast<int>(seq.size());
    const int max_len = std::min({len, 10, count - removed});
    const int length = std::uniform_int_distribution<int>(1, std::max(1, max_len))(rng_);
    const int at = static_cast<int>(std::find(seq.begin(), seq.end(), m_.requests()[q].first) - seq.begin());
    const int first = std::clamp(at - std::uniform_int_distribution<int>(0, length - 1)(rng_), 0, len - length);
    for (int k = first; k < first + length; ++k) {
      const int request = m_.request_of(seq[k]);
      if (s.route_of[seq[k]] < 0) continue;  // its pickup or drop went already
      sol_.remove(s, request);
      ++removed;
    }
  }
}

void FleetSearch::ruin_route(FleetSolution& s) {
  // The smallest of three nonempty routes drawn at random.
  std::vector<int> used;
  for (int r = 0; r < static_cast<int>(s.routes.size()); ++r)
    if (!s.routes[r].empty()) used.push_back(r);
  if (used.empty()) return;
  int pick = -1;
  for (int k = 0; k < 3; ++k) {
    const int r = used[std::uniform_int_distribution<std::size_t>(0, used.size() - 1)(rng_)];
    if (pick < 0 || s.routes[r].seq.size() < s.routes[pick].seq.size()) pick = r;
  }
  const std::vector<int> seq = s.routes[pick].seq;
  for (int x : seq)
    if (s.route_of[x] >= 0) sol_.remove(s, m_.request_of(x));
}

}  // namespace rondo::schedule::detail
