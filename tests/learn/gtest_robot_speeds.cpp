// RobotSpeeds: a fleet's robots' paces recovered from one log, against an exact least-squares
// solve on small logs (the slow reference), and its invariants as properties.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "rondo/learn/robot_speeds.h"

namespace rondo::learn {
namespace {

const Time kT0 = Time{} + hours(24 * 20000);

Traversal crossing(const std::string& robot, int edge, double seconds, bool success = true) {
  return {.edge_id = "e" + std::to_string(edge),
          .from = "n" + std::to_string(edge),
          .to = "n" + std::to_string(edge + 1),
          .start = kT0,
          .duration = from_seconds(seconds),
          .success = success,
          .robot = robot};
}

TEST(RobotSpeeds, ALoneRobotIsTheStandard) {
  const std::vector<Traversal> log = {crossing("r1", 0, 10), crossing("r1", 1, 30), crossing("r1", 0, 12)};
  const RobotSpeeds speeds = RobotSpeeds::fit(log);
  EXPECT_TRUE(speeds.factors().empty());
  EXPECT_EQ(speeds.standardised(log), log);
  EXPECT_EQ(speeds.own_time("r1", seconds(40)), seconds(40));
}

// Three robots at 1, 0.8 and 1.25 of a pace on twelve edges with noisy times: their ratios come
// back within 3 %, and the standardised log has one pace.
TEST(RobotSpeeds, RecoversTheRatiosOfPaces) {
  std::mt19937_64 rng(7);
  std::lognormal_distribution<double> noise(0.0, 0.2);
  const std::vector<std::pair<std::string, double>> robots = {{"r1", 1.0}, {"slow", 0.8}, {"fast", 1.25}};
  std::vector<Traversal> log;
  for (int k = 0; k < 60; ++k)
    for (int e = 0; e < 12; ++e)
      for (const auto& [name, speed] : robots) log.push_back(crossing(name, e, (10.0 + 5 * e) * noise(rng) / speed));
  log.push_back(crossing("slow", 0, 1000, false));  // a failure: not fitted
  const RobotSpeeds speeds = RobotSpeeds::fit(log);
  EXPECT_NEAR(speeds.factor("slow") / speeds.factor("r1"), 0.8, 0.8 * 0.03);
  EXPECT_NEAR(speeds.factor("fast") / speeds.factor("r1"), 1.25, 1.25 * 0.03);
  EXPECT_EQ(speeds.factor("someone else"), 1.0);
  EXPECT_NEAR(speeds.factor("r1") * speeds.factor("slow") * speeds.factor("fast"), 1.0, 1e-9);  // equal weights
  const std::vector<Traversal> standard = speeds.standardised(log);
  EXPECT_NEAR(to_seconds(standard.back().duration), 1000 * speeds.factor("slow"), 1e-3);  // failures scale too
}

// A robot seen on few attempts is drawn towards the fleet's pace, less so as its attempts grow. One
// attempt at half r1's pace: the ridge (4 on each of the two paces) splits the log-ratio as a
// Gaussian prior of spread 0.2 against attempt noise 0.4 would, to exp(−0.228) = 0.80 of r1's.
TEST(RobotSpeeds, FewAttemptsAreDrawnTowardsTheFleetsPace) {
  std::vector<Traversal> log;
  for (int k = 0; k < 50; ++k) log.push_back(crossing("r1", 0, 10));
  log.push_back(crossing("new", 0, 20));
  const RobotSpeeds one = RobotSpeeds::fit(log);
  EXPECT_NEAR(one.factor("new") / one.factor("r1"), 0.796, 0.005);
  for (int k = 0; k < 9; ++k) log.push_back(crossing("new", 0, 20));
  const RobotSpeeds ten = RobotSpeeds::fit(log);
  EXPECT_GT(ten.factor("new") / ten.factor("r1"), 0.5);
  EXPECT_LT(ten.factor("new") / ten.factor("r1"), one.factor("new") / one.factor("r1"));
}

// The slow reference: the normal equations of min Σ (y − a_e − b_r)² + k Σ b_r², solved by
// Gaussian elimination with partial pivoting, then b centred as RobotSpeeds centres it.
std::map<std::string, double> reference(const std::vector<Traversal>& log, double k) {
  std::map<std::string, std::size_t> edges, robots;
  for (const Traversal& t : log) {
    edges.emplace(t.edge_id, 0);
    robots.emplace(t.robot, 0);
  }
  std::size_t n = 0;
  for (auto& [name, i] : edges) i = n++;
  const std::size_t first_robot = n;
  for (auto& [name, i] : robots) i = n++;
  std::vector<std::vector<double>> m(n, std::vector<double>(n + 1, 0.0));
  for (const Traversal& t : log) {
    const std::size_t e = edges[t.edge_id], r = robots[t.robot];
    const double y = std::log(to_seconds(t.duration));
    m[e][e] += 1;
    m[e][r] += 1;
    m[r][e] += 1;
    m[r][r] += 1;
    m[e][n] += y;
    m[r][n] += y;
  }
  for (std::size_t r = first_robot; r < n; ++r) m[r][r] += k;
  for (std::size_t c = 0; c < n; ++c) {
    std::size_t p = c;
    for (std::size_t i = c + 1; i < n; ++i)
      if (std::abs(m[i][c]) > std::abs(m[p][c])) p = i;
    std::swap(m[c], m[p]);
    for (std::size_t i = 0; i < n; ++i) {
      if (i == c) continue;
      const double f = m[i][c] / m[c][c];
      for (std::size_t j = c; j <= n; ++j) m[i][j] -= f * m[c][j];
    }
  }
  double mean = 0, total = 0;
  std::map<std::string, double> b;
  for (const auto& [name, r] : robots) {
    b[name] = m[r][n] / m[r][r];
    double w = 0;
    for (const Traversal& t : log) w += t.robot == name ? 1 : 0;
    mean += w * b[name];
    total += w;
  }
  std::map<std::string, double> factors;
  for (const auto& [name, v] : b) factors[name] = std::exp(mean / total - v);
  return factors;
}

std::vector<Traversal> random_log() {
  const int robots = *rc::gen::inRange(2, 4);
  const int edges = *rc::gen::inRange(1, 5);
  const int n = *rc::gen::inRange(1, 25);
  std::vector<Traversal> log;
  for (int i = 0; i < n; ++i)
    log.push_back(crossing("r" + std::to_string(*rc::gen::inRange(0, robots)), *rc::gen::inRange(0, edges),
                           *rc::gen::inRange(1, 600) / 4.0));
  return log;
}

RC_GTEST_PROP(RobotSpeeds, AgreeWithTheExactLeastSquaresSolve, ()) {
  const std::vector<Traversal> log = random_log();
  const double k = *rc::gen::element(0.5, 5.0, 20.0);
  const RobotSpeeds speeds = RobotSpeeds::fit(log, {.prior_attempts = k, .max_sweeps = 100000, .tolerance = 1e-13});
  const auto exact = reference(log, k);
  if (exact.size() < 2) {
    RC_ASSERT(speeds.factors().empty());
    return;
  }
  for (const auto& [name, f] : exact) {
    const double clamped = std::clamp(f, 0.25, 4.0);
    RC_ASSERT(std::abs(speeds.factor(name) - clamped) <= 1e-6 * clamped);
  }
}

// Timing every attempt with a slower or faster clock changes nothing: the pace is relative.
RC_GTEST_PROP(RobotSpeeds, ACommonScaleChangesNoFactor, ()) {
  std::vector<Traversal> log = random_log();
  const RobotSpeeds before = RobotSpeeds::fit(log);
  const double c = *rc::gen::element(0.5, 2.0, 3.0);  // exact in milliseconds on quarter seconds
  for (Traversal& t : log) t.duration = from_seconds(to_seconds(t.duration) * c);
  const RobotSpeeds after = RobotSpeeds::fit(log);
  for (const auto& [name, f] : before.factors()) RC_ASSERT(std::abs(after.factor(name) - f) <= 1e-6 * f);
}

}  // namespace
}  // namespace rondo::learn
