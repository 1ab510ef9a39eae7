#include "rondo/plan/mdp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>

#include "region_search.h"

namespace rondo::plan {

EdgeCrossing sanitize(EdgeCrossing raw) {
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

double expected_crossing_seconds(const EdgeCrossing& sanitized) {
  if (!(sanitized.success_probability > 0.0)) return kInfinity;
  const double c = sanitized.expected_seconds / sanitized.success_probability;
  return std::isfinite(c) ? c : kInfinity;
}

Mdp::Mdp(const map::TopoMap& map, std::vector<EdgeCrossing> outcomes, Time at, std::shared_ptr<const DeadEnds> dead_ends)
    : map_(&map), at_(at), outcomes_(std::move(outcomes)), dead_ends_(std::move(dead_ends)) {
  if (!dead_ends_) dead_ends_ = std::make_shared<const DeadEnds>(DeadEnds::find(map));
  if (dead_ends_->node_count() != map.node_count()) {
    throw std::invalid_argument("Mdp: the dead ends are of another map (node counts differ)");
  }
  crossing_.reserve(outcomes_.size());
  for (EdgeCrossing& o : outcomes_) {
    o = sanitize(o);
    crossing_.push_back(plan::expected_crossing_seconds(o));
  }
  build_rows();
  build_dead_ends();
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

void Mdp::build_dead_ends() {
  const std::size_t n = map_->node_count();
  if (dead_ends_->region_count() == 0) return;
  core_start_.assign(n + 1, 0);
  for (NodeIndex v = 0; v < n; ++v) {
    core_start_[v] = core_arcs_.size();
    if (!dead_ends_->in_core(v)) continue;
    for (const InArc& arc : usable_in(v)) {
      if (dead_ends_->in_core(arc.from)) core_arcs_.push_back(arc);
    }
  }
  core_start_[n] = core_arcs_.size();

  // Each region's routes to its door; the scratch is reset only where a search wrote.
  std::vector<double> cost(n, kInfinity);
  std::vector<EdgeIndex> edge(n, kNoExit);
  std::vector<std::uint8_t> settled(n, 0);
  exits_.reserve(dead_ends_->region_members().size());
  for (std::uint32_t r = 0; r < dead_ends_->region_count(); ++r) {
    const NodeIndex door = dead_ends_->door(r);
    detail::search_region(*this, r, door, cost, edge, settled);
    for (NodeIndex v : dead_ends_->nodes(r)) {
      exits_.push_back({.seconds = cost[v], .edge = edge[v]});
      cost[v] = kInfinity;
      edge[v] = kNoExit;
      settled[v] = 0;
    }
    cost[door] = kInfinity;
    settled[door] = 0;
  }
}

Mdp Mdp::build(const map::TopoMap& map, const EdgeModelView& models, Time at,
               std::shared_ptr<const DeadEnds> dead_ends) {
  std::vector<EdgeCrossing> outcomes;
  outcomes.reserve(map.edge_count());
  for (EdgeIndex e = 0; e < map.edge_count(); ++e) outcomes.push_back(models.outcome(e, at));
  return Mdp(map, std::move(outcomes), at, std::move(dead_ends));
}

Result<Mdp> Mdp::from_outcomes(const map::TopoMap& map, std::vector<EdgeCrossing> outcomes, Time at,
                               std::shared_ptr<const DeadEnds> dead_ends) {
  if (outcomes.size() != map.edge_count()) {
    return Error::invalid(fmt::format("{} edge outcomes for a map with {} edges", outcomes.size(), map.edge_count()));
  }
  if (dead_ends && dead_ends->node_count() != map.node_count()) {
    return Error::invalid(fmt::format("dead ends of a map with {} nodes for a map with {} nodes",
                                      dead_ends->node_count(), map.node_count()));
  }
  return Mdp(map, std::move(outcomes), at, std::move(dead_ends));
}

}  // namespace rondo::plan
