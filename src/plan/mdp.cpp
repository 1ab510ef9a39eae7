#include "rondo/plan/mdp.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace rondo::plan {

EdgeOutcome sanitize(EdgeOutcome raw) {
  double p = raw.success_probability;
  p = std::isnan(p) ? 0.0 : std::clamp(p, 0.0, 1.0);
  double tau = raw.expected_seconds;
  if (std::isnan(tau) || tau == kInfinity) {
    tau = kInfinity;
  } else {
    tau = std::max(tau, kMinAttemptSeconds);  // also lifts negative and -inf values
  }
  return {.success_probability = p, .expected_seconds = tau};
}

double expected_crossing_seconds(const EdgeOutcome& sanitized) {
  if (!(sanitized.success_probability > 0.0)) return kInfinity;
  const double c = sanitized.expected_seconds / sanitized.success_probability;
  return std::isfinite(c) ? c : kInfinity;
}

Mdp::Mdp(const map::TopoMap& map, std::vector<EdgeOutcome> outcomes, Time at)
    : map_(&map), at_(at), outcomes_(std::move(outcomes)) {
  crossing_.reserve(outcomes_.size());
  for (EdgeOutcome& o : outcomes_) {
    o = sanitize(o);
    crossing_.push_back(plan::expected_crossing_seconds(o));
  }
  build_rows();
}

void Mdp::build_rows() {
  const std::size_t n = map_->node_count();
  in_start_.assign(n + 1, 0);
  out_start_.assign(n + 1, 0);
  for (NodeIndex v = 0; v < n; ++v) {
    in_start_[v] = in_arcs_.size();
    for (EdgeIndex e : map_->in_edges(v)) {
      if (!usable(e)) continue;
      in_arcs_.push_back({map_->from_index(e), e, crossing_[e]});
      min_crossing_ = std::min(min_crossing_, crossing_[e]);
      max_crossing_ = std::max(max_crossing_, crossing_[e]);
    }
    out_start_[v] = out_arcs_.size();
    for (EdgeIndex e : map_->out_edges(v)) {
      if (usable(e)) {
        out_arcs_.push_back({map_->to_index(e), e, outcomes_[e].success_probability, outcomes_[e].expected_seconds});
      }
    }
  }
  in_start_[n] = in_arcs_.size();
  out_start_[n] = out_arcs_.size();
}

Mdp Mdp::build(const map::TopoMap& map, const EdgeModelView& models, Time at) {
  std::vector<EdgeOutcome> outcomes;
  outcomes.reserve(map.edge_count());
  for (EdgeIndex e = 0; e < map.edge_count(); ++e) outcomes.push_back(models.outcome(e, at));
  return Mdp(map, std::move(outcomes), at);
}

Result<Mdp> Mdp::from_outcomes(const map::TopoMap& map, std::vector<EdgeOutcome> outcomes, Time at) {
  if (outcomes.size() != map.edge_count()) {
    return Error::invalid(fmt::format("{} edge outcomes for a map with {} edges", outcomes.size(), map.edge_count()));
  }
  return Mdp(map, std::move(outcomes), at);
}

}  // namespace rondo::plan
