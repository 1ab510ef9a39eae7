#include "rondo/learn/robot_speeds.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace rondo::learn {
namespace {

struct Attempt {
  std::size_t edge;
  std::size_t robot;
  double y;  // log seconds
};

// The successful attempts of named robots with a duration, edges and robots numbered in order of
// their names (so the fit does not depend on the log's order beyond its sums).
struct Design {
  std::vector<Attempt> attempts;
  std::vector<std::string> robots;
  std::size_t edges = 0;
};

Design design_of(std::span<const Traversal> log) {
  std::map<std::string_view, std::size_t> edges, robots;
  for (const Traversal& t : log)
    if (t.success && !t.robot.empty() && t.duration > Duration{0}) {
      edges.emplace(t.edge_id, 0);
      robots.emplace(t.robot, 0);
    }
  Design d;
  for (auto& [name, i] : edges) i = d.edges++;
  for (auto& [name, i] : robots) {
    i = d.robots.size();
    d.robots.emplace_back(name);
  }
  for (const Traversal& t : log)
    if (t.success && !t.robot.empty() && t.duration > Duration{0})
      d.attempts.push_back({edges.at(t.edge_id), robots.at(t.robot), std::log(to_seconds(t.duration))});
  return d;
}

// One sweep: a from b (exact), then b from a (exact, with the ridge). Returns the largest change of b.
double sweep(const Design& d, std::vector<double>& a, std::vector<double>& b, double ridge) {
  std::vector<double> sum(d.edges, 0.0), count(d.edges, 0.0);
  for (const Attempt& x : d.attempts) {
    sum[x.edge] += x.y - b[x.robot];
    count[x.edge] += 1;
  }
  for (std::size_t e = 0; e < d.edges; ++e) a[e] = sum[e] / count[e];
  std::vector<double> rsum(b.size(), 0.0), rcount(b.size(), 0.0);
  for (const Attempt& x : d.attempts) {
    rsum[x.robot] += x.y - a[x.edge];
    rcount[x.robot] += 1;
  }
  double change = 0;
  for (std::size_t r = 0; r < b.size(); ++r) {
    const double next = rsum[r] / (rcount[r] + ridge);
    change = std::max(change, std::abs(next - b[r]));
    b[r] = next;
  }
  return change;
}

}  // namespace

RobotSpeeds RobotSpeeds::fit(std::span<const Traversal> log, const RobotSpeedOptions& options) {
  const Design d = design_of(log);
  if (d.robots.size() < 2) return RobotSpeeds{};
  std::vector<double> a(d.edges, 0.0), b(d.robots.size(), 0.0);
  for (int i = 0; i < options.max_sweeps; ++i)
    if (sweep(d, a, b, options.prior_attempts) <= options.tolerance) break;
  std::vector<double> weight(b.size(), 0.0);
  for (const Attempt& x : d.attempts) weight[x.robot] += 1;
  double mean = 0, total = 0;
  for (std::size_t r = 0; r < b.size(); ++r) {
    mean += weight[r] * b[r];
    total += weight[r];
  }
  mean /= total;
  std::map<std::string, double, std::less<>> factors;
  for (std::size_t r = 0; r < b.size(); ++r)
    factors.emplace(d.robots[r], std::clamp(std::exp(mean - b[r]), options.min_factor, options.max_factor));
  return RobotSpeeds(std::move(factors));
}

double RobotSpeeds::factor(std::string_view robot) const {
  const auto it = factors_.find(robot);
  return it == factors_.end() ? 1.0 : it->second;
}

std::vector<Traversal> RobotSpeeds::standardised(std::span<const Traversal> log) const {
  std::vector<Traversal> out;
  out.reserve(log.size());
  for (const Traversal& t : log) out.push_back(standardised(t));
  return out;
}

Traversal RobotSpeeds::standardised(Traversal attempt) const {
  if (const double f = factor(attempt.robot); f != 1.0)
    attempt.duration = from_seconds(to_seconds(attempt.duration) * f);
  return attempt;
}

Duration RobotSpeeds::own_time(std::string_view robot, Duration standard) const {
  const double f = factor(robot);
  return f == 1.0 ? standard : from_seconds(to_seconds(standard) / f);
}

}  // namespace rondo::learn
