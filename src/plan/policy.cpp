#include "rondo/plan/policy.h"

#include <stdexcept>

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

std::vector<PolicyStep> Policy::route(NodeIndex from) const {
  std::vector<PolicyStep> out;
  NodeIndex at = from;
  while (at != target_ && steps_.at(at).edge != kNoEdge && out.size() < steps_.size()) {
    out.push_back(steps_[at]);
    at = steps_[at].to;
  }
  return out;
}

TravelTimeDistribution Policy::travel_time_distribution(NodeIndex from, const DistributionOptions& options) const {
  if (!reaches_target(from)) return TravelTimeDistribution::unreachable();
  std::vector<RouteLeg> legs;
  for (const PolicyStep& s : route(from)) legs.push_back({s.success_probability, s.attempt_seconds});
  return TravelTimeDistribution::of_route(legs, options);
}

}  // namespace rondo::plan
