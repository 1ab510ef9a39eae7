// A navigation policy to one target node: for every node, the edge to try next and the expected
// time to reach the target from there (retries included), as the solvers (exact_solver.h,
// value_iteration.h) return it. Also the route the policy takes and the distribution of its
// travel time, for the probability of arriving within a budget.
//
//   Solution s = ExactSolver{}.solve(mdp, target).value();
//   const Policy& policy = s.policy;
//   if (auto e = policy.next_edge(here)) robot.navigate(*e);
//   double eta = policy.expected_seconds(here);                  // +inf when unreachable
//   TravelTimeDistribution d = policy.travel_time_distribution(here);
//   double p_on_time = d.probability_within(600.0).estimate();
//
// A Policy copies the few numbers of each chosen edge it needs, so it stays valid after the Mdp
// it came from is gone.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "rondo/map/topo_map.h"
#include "rondo/plan/travel_time_distribution.h"

namespace rondo::plan {

using map::EdgeIndex;
using map::NodeIndex;

// One step of a policy: from `from`, try `edge` (to `to`) until it succeeds.
struct PolicyStep {
  NodeIndex from = 0;
  EdgeIndex edge = 0;
  NodeIndex to = 0;
  double success_probability = 1.0;  // of one attempt, in (0, 1]
  double attempt_seconds = 0.0;      // duration of one attempt
  bool operator==(const PolicyStep&) const = default;
};

class Policy {
 public:
  static constexpr EdgeIndex kNoEdge = std::numeric_limits<EdgeIndex>::max();

  // `next_edge[i]` is kNoEdge for the target and for nodes that cannot reach it; then
  // `expected_seconds[i]` is 0 for the target and +inf for the others. `steps[i]` describes the
  // chosen edge of node i (ignored where next_edge is kNoEdge). The solvers build policies; the
  // constructor only checks sizes (std::invalid_argument on misuse).
  Policy(NodeIndex target, std::vector<PolicyStep> steps, std::vector<double> expected_seconds);

  NodeIndex target() const { return target_; }
  std::size_t node_count() const { return expected_.size(); }

  // Preconditions below: node < node_count().
  bool reaches_target(NodeIndex node) const { return node == target_ || steps_[node].edge != kNoEdge; }
  // The edge to try from `node`; nothing at the target and at nodes that cannot reach it.
  std::optional<EdgeIndex> next_edge(NodeIndex node) const;
  // Expected seconds from `node` to the target following this policy: 0 at the target, +inf when
  // the target cannot be reached.
  double expected_seconds(NodeIndex node) const { return expected_[node]; }
  // The chosen step at `node`; nothing where next_edge() is nothing.
  std::optional<PolicyStep> step(NodeIndex node) const;

  // The steps from `from` to the target (empty at the target and when unreachable). A policy from
  // a solver never loops; a malformed one is cut after node_count() steps.
  std::vector<PolicyStep> route(NodeIndex from) const;

  // The distribution of the time to reach the target from `from` (see travel_time_distribution.h
  // for the method and its accuracy). An unreachable target gives a distribution with all its mass
  // at +inf. With `laws`, each step's leg ({p, τ}) is handed to it to fill its duration laws.
  using LegLaws = std::function<void(const PolicyStep&, RouteLeg&)>;
  TravelTimeDistribution travel_time_distribution(NodeIndex from, const DistributionOptions& options = {},
                                                  const LegLaws& laws = {}) const;

  // Whether this policy stays optimal, with expected_seconds() unchanged, after the expected
  // crossing time τ/p of `edge` (from `from` to `to`) becomes `crossing` (+inf: unusable). That
  // holds exactly when the policy does not take the edge and the edge did not become a shortcut
  // (crossing + V(to) >= V(from)), or when it takes the edge and its crossing time is the same.
  // The optimal values of a shortest-path MDP are unique, so a fresh solve gives the same
  // expected_seconds() (its choice between tied edges may differ).
  bool survives_edge_change(EdgeIndex edge, NodeIndex from, NodeIndex to, double crossing) const;

 private:
  NodeIndex target_;
  std::vector<PolicyStep> steps_;
  std::vector<double> expected_;
};

}  // namespace rondo::plan
