// The distribution of the time a policy takes to reach its target: a sum over the route's edges of
// (number of attempts) × (attempt duration), each number of attempts geometric with the edge's
// success probability. Used for the probability of arriving within a budget and for quantiles.
//
//   std::vector<RouteLeg> legs = {{.success_probability = 0.8, .attempt_seconds = 12.0}, ...};
//   TravelTimeDistribution d = TravelTimeDistribution::of_route(legs);
//   ProbabilityBounds p = d.probability_within(300.0);   // p.lower <= P(T <= 300 s) <= p.upper
//   double q90 = d.quantile(0.9).upper;                  // never below the true 0.9-quantile
//
// Method and accuracy (docs/planning.md, "Travel-time distribution"): the attempt counts are
// independent, so T = Σ_k N_k τ_k with N_k ~ Geometric(p_k) on {1, 2, ...}. On a grid of cell
// width h over [0, horizon], the law of N·m cells (m = τ/h) is added to a running distribution by
// the exact recurrence g[x] = p·f[x−m] + (1−p)·g[x−m], O(cells) per edge. Doing it twice, with
// every τ_k rounded down and rounded up to whole cells, gives two distributions that are exact for
// travel times T⁻ <= T <= T⁺; so every probability and quantile comes as a guaranteed bracket
// [lower, upper]. The bracket is as wide as the rounding: T⁺ − T⁻ <= h × (total attempts), so with
// the default grid (4096 cells over 16 × the expected time) quantiles are bracketed to within
// about 0.4% of the expected time per expected attempt; when every τ is a whole number of cells the
// bracket closes and the answer is exact. Mass beyond the horizon is kept as a tail and never
// counted as "within budget".
//
// Attempt durations. Without laws, every attempt of an edge lasts its attempt_seconds. A leg may
// instead carry two small discrete laws: the duration of a successful attempt and that of a failed
// one (weighted points, seconds). Crossing the edge then takes F_1 + ... + F_(N−1) + S, with N
// geometric as above, the F_i from the failure law and S from the success law, all independent.
// Its law X satisfies X = S with probability p, F + X' otherwise, so g = f * X is found by
// g[x] = p (f * S)[x] + (1 − p) Σ_j F_j g[x − j] (a point of F at 0 cells is moved to the left
// side), O(cells × points) per edge. Every point is rounded down and up to whole cells, which keeps
// the bracket guaranteed. A leg with only one of the two laws uses attempt_seconds for the other.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace rondo::plan {

// One point of a discrete duration law: `seconds` (>= 0, finite) with weight `weight` (> 0; a law's
// weights are normalised, points with other weights are dropped).
struct DurationPoint {
  double seconds = 0.0;
  double weight = 0.0;
  bool operator==(const DurationPoint&) const = default;
};

// One edge of a route, as the distribution sees it.
struct RouteLeg {
  double success_probability = 1.0;  // in (0, 1]
  double attempt_seconds = 0.0;      // >= 0, finite
  // Optional laws of one successful / one failed attempt's duration; empty: attempt_seconds.
  std::vector<DurationPoint> success_law{};
  std::vector<DurationPoint> failure_law{};
};

// The attempts of one edge that were stopped before they ended (right-censored: each would have
// run longer, and how it would have ended is not known): their share of all the edge's attempts
// (succeeded, failed or stopped) and the law of how long they had run when stopped, in seconds. A
// lower bound of the tail the traversal log cannot see (exec/attempt_laws.h).
struct StoppedAttempts {
  double share = 0.0;                // in [0, 1]; 0: none
  std::vector<DurationPoint> law{};  // seconds run before the stop
  bool operator==(const StoppedAttempts&) const = default;
};

// Duration laws shared by every edge, as multiples of an edge's expected attempt seconds: leg k
// gets the points {seconds × τ_k, weight}. Learned from the traversal log at refit time
// (exec/attempt_laws.h). Empty laws leave attempt_seconds fixed. `stopped`, by map edge index
// (shorter than the map: none for the rest), makes a stopped attempt a third way an attempt of
// that edge goes (LearnedEdgeModels::attempt_laws).
struct AttemptLaws {
  std::vector<DurationPoint> success{};  // one successful attempt / τ
  std::vector<DurationPoint> failure{};  // one failed attempt / τ
  std::vector<StoppedAttempts> stopped{};
  bool operator==(const AttemptLaws&) const = default;
};

struct DistributionOptions {
  std::size_t cells = 4096;      // grid resolution, >= 16 (smaller values are raised to 16)
  double horizon_factor = 16.0;  // the grid spans [0, horizon_factor × expected time], >= 2
  // Only the first `computed_cells` cells of that grid are computed (0, or more than `cells`: all
  // of them); the rest lies beyond the grid. The cell width stays that of the whole grid, and every
  // value within the cells computed is the whole grid's to the bit: travel times only grow along a
  // route, so mass that is past a cell never comes back to it. A quantile beyond them (upper +inf)
  // can be asked again of the whole grid.
  std::size_t computed_cells = 0;
};

// A probability known to lie in [lower, upper]; both in [0, 1].
struct ProbabilityBounds {
  double lower = 0.0;
  double upper = 0.0;
  double estimate() const { return 0.5 * (lower + upper); }
};

// A quantile known to lie in [lower, upper] seconds; upper is +inf when it lies beyond the grid.
struct QuantileBounds {
  double lower = 0.0;
  double upper = 0.0;
};

class TravelTimeDistribution {
 public:
  // The time to cross `legs` in order. Legs with success_probability <= 0 or a non-finite
  // attempt_seconds make the whole route unreachable. No legs: the target is already reached (T=0).
  static TravelTimeDistribution of_route(std::span<const RouteLeg> legs, const DistributionOptions& options = {});
  // The target cannot be reached: T = +inf with certainty.
  static TravelTimeDistribution unreachable();

  bool reachable() const { return reachable_; }
  // E[T] = Σ τ_k / p_k, exact (not from the grid); +inf when unreachable. With laws, each leg
  // contributes E[S] + E[F] (1 − p) / p instead.
  double expected_seconds() const { return expected_; }
  // Bounds on P(T <= budget_seconds).
  ProbabilityBounds probability_within(double budget_seconds) const;
  // Bounds on the q-quantile inf{b : P(T <= b) >= q}, q in (0, 1] (clamped to it).
  QuantileBounds quantile(double q) const;

  double cell_seconds() const { return cell_; }
  // The end of the cells computed (DistributionOptions::computed_cells).
  double horizon_seconds() const { return cell_ * static_cast<double>(cells_); }
  // An upper bound on P(T > horizon): the mass the rounded-up pass pushed beyond the grid.
  double tail_mass() const;

 private:
  TravelTimeDistribution() = default;

  bool reachable_ = true;
  double expected_ = 0.0;
  double cell_ = 0.0;
  std::size_t cells_ = 0;
  // Cumulative distributions over grid points 0..cells_ of the rounded-down (fast) and rounded-up
  // (slow) travel times: fast_cdf_ >= the true CDF >= slow_cdf_ at every grid point.
  std::vector<double> fast_cdf_;
  std::vector<double> slow_cdf_;
};

}  // namespace rondo::plan
