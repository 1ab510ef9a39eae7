#include "rondo/plan/policy.h"

#include <stdexcept>

#include "rondo/plan/mdp.h"

namespace rondo::plan {

Policy::Policy(NodeIndex target, std::vector<PolicyStep> steps, std::vector<double> expected_seconds)
    : target_(target),
      steps_(std::move(steps)),
      expected_(std::move(expected_seconds)) {
  if (steps_.size() != expected_.size() || target_ >= expected_.size()) {
    throw std::invalid_argument("Policy: one step and one expected time per node, and a target among the nodes");
  }
  // The target has no step: a solver may leave one there, it is never taken.
  steps_[target_].edge = kNoEdge;
}

std::optional<EdgeIndex> Policy::next_edge(NodeIndex node) const {
  if (steps_.at(node).edge == kNoEdge) return std::nullopt;
  return steps_[node].edge;
}

std::optional<PolicyStep> Policy::step(NodeIndex node) const {
  if (steps_.at(node).edge == kNoEdge) return std::nullopt;
  return steps_[node];
}

bool Policy::survives_edge_change(EdgeIndex edge, NodeIndex from, NodeIndex to, double crossing) const {
  if (from >= expected_.size() || to >= expected_.size()) return false;
  if (from == target_) return true;  // no step leaves the target
  const PolicyStep& s = steps_[from];
  if (s.edge == edge) {
    return crossing == expected_crossing_seconds(sanitize(
                           {.success_probability = s.success_probability, .expected_seconds = s.attempt_seconds}));
  }
  return !(crossing + expected_[to] < expected_[from]);
}

std::vector<PolicyStep> Policy::route(NodeIndex from) const {
  std::vector<PolicyStep> out;
  NodeIndex at = from;
  while (at != target_ && steps_.at(at).edge != kNoEdge && out.size() < steps_.size()) {
    out.push_back(steps_[at]);
    at = steps_[at].to;
  }
  return out;
}

TravelTimeDistribution Policy::travel_time_distribution(NodeIndex from, const DistributionOptions& options,
                                                        const LegLaws& laws) const {
  if (!reaches_target(from)) return TravelTimeDistribution::unreachable();
  std::vector<RouteLeg> legs;
  for (const PolicyStep& s : route(from)) {
    legs.push_back({s.success_probability, s.attempt_seconds});
    if (laws) laws(s, legs.back());
  }
  return TravelTimeDistribution::of_route(legs, options);
}

}  // namespace rondo::plan
