// M_t, the navigation MDP at one departure time t (MISSION.md §4): states are the map's nodes,
// actions are their out-edges; taking edge e = (i, j) reaches j with probability p_e(t) and stays
// at i otherwise, and costs τ_e(t) seconds either way. An Mdp is a snapshot: the edge outcomes
// are read once, at t, and sanitised so that the solvers never see NaN or negative numbers.
//
//   DistancePrior prior(map);
//   Mdp mdp = Mdp::build(map, prior, depart_at);
//   double c = mdp.expected_crossing_seconds(e);   // τ/p, retries included; +inf if unusable
//
// Lifetime: an Mdp refers to its map (topology and node names); the map must outlive it.
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/dead_ends.h"
#include "rondo/plan/edge_model_view.h"

namespace rondo::plan {

using map::EdgeIndex;
using map::NodeIndex;

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();
// The shortest attempt the planner believes in. Zero-cost edges would let value iteration settle
// on zero-cost cycles that never reach the target; no real attempt takes less than a millisecond.
inline constexpr double kMinAttemptSeconds = 1e-3;

class Mdp {
 public:
  // Reads models.outcome(e, at) for every edge of `map`. `dead_ends`: the map's, from
  // DeadEnds::find(map), to share one between the many M_t of a map (they depend on its topology
  // only); found here when null.
  static Mdp build(const map::TopoMap& map, const EdgeModelView& models, Time at,
                   std::shared_ptr<const DeadEnds> dead_ends = nullptr);
  // The same from outcomes given directly, one per edge; an error if the count is wrong or
  // `dead_ends` is not of a map with this many nodes.
  static Result<Mdp> from_outcomes(const map::TopoMap& map, std::vector<EdgeCrossing> outcomes, Time at,
                                   std::shared_ptr<const DeadEnds> dead_ends = nullptr);

  const map::TopoMap& topology() const { return *map_; }
  Time time() const { return at_; }
  std::size_t node_count() const { return map_->node_count(); }
  std::size_t edge_count() const { return outcomes_.size(); }

  // The sanitised outcome of an attempt on `edge`: p in [0, 1]; τ >= kMinAttemptSeconds, or +inf
  // for an edge whose model gave NaN or +inf. Precondition: edge < edge_count().
  const EdgeCrossing& outcome(EdgeIndex edge) const { return outcomes_[edge]; }
  // τ/p: the expected time to cross `edge` by trying until it succeeds; +inf when p = 0, τ is
  // +inf, or the quotient overflows. Such edges are unusable: no policy takes them.
  double expected_crossing_seconds(EdgeIndex edge) const { return crossing_[edge]; }
  bool usable(EdgeIndex edge) const { return crossing_[edge] < kInfinity; }
  // The smallest and largest τ/p over usable edges; +inf and 0 when no edge is usable.
  double min_crossing_seconds() const { return min_crossing_; }
  double max_crossing_seconds() const { return max_crossing_; }

  // The usable edges in compressed rows (CSR), for the solvers' inner loops: contiguous arrays,
  // no unusable edge, no lookups. Rows keep the map's in_edges / out_edges order.
  struct InArc {
    NodeIndex from;
    EdgeIndex edge;
    double crossing_seconds;  // τ/p
  };
  struct OutArc {
    NodeIndex to;
    EdgeIndex edge;
    double success_probability;
    double attempt_seconds;
  };
  // Preconditions: node < node_count().
  std::span<const InArc> usable_in(NodeIndex node) const {
    return {in_arcs_.data() + in_start_[node], in_arcs_.data() + in_start_[node + 1]};
  }
  std::span<const OutArc> usable_out(NodeIndex node) const {
    return {out_arcs_.data() + out_start_[node], out_arcs_.data() + out_start_[node + 1]};
  }

  // The map's dead ends (dead_ends.h), found when M_t is built, and what the exact solver needs
  // of them: the usable in-arcs of each core node that come from core nodes (none for region
  // nodes), and each region node's best way to its region's door inside the region, at t.
  const DeadEnds& dead_ends() const { return *dead_ends_; }
  std::span<const InArc> core_in(NodeIndex node) const {
    if (core_start_.empty()) return usable_in(node);  // no dead ends: every node is in the core
    return {core_arcs_.data() + core_start_[node], core_arcs_.data() + core_start_[node + 1]};
  }
  static constexpr EdgeIndex kNoExit = std::numeric_limits<EdgeIndex>::max();
  struct Exit {
    double seconds;  // expected time to the door; +inf when the door cannot be reached
    EdgeIndex edge;  // the edge to take first; kNoExit when seconds is +inf
  };
  // One per node of DeadEnds::region_members(), in that order.
  std::span<const Exit> exits() const { return exits_; }

 private:
  Mdp(const map::TopoMap& map, std::vector<EdgeCrossing> outcomes, Time at, std::shared_ptr<const DeadEnds> dead_ends);
  void build_rows();
  void build_dead_ends();

  const map::TopoMap* map_;
  Time at_;
  std::vector<EdgeCrossing> outcomes_;
  std::vector<double> crossing_;
  double min_crossing_ = kInfinity, max_crossing_ = 0.0;
  std::vector<std::size_t> in_start_, out_start_;  // node_count() + 1 each
  std::vector<InArc> in_arcs_;
  std::vector<OutArc> out_arcs_;
  std::shared_ptr<const DeadEnds> dead_ends_;
  std::vector<std::size_t> core_start_;  // node_count() + 1; empty when there are no dead ends
  std::vector<InArc> core_arcs_;
  std::vector<Exit> exits_;
};

// The sanitising rule of Mdp, exposed for tests and for callers that build costs themselves.
EdgeCrossing sanitize(EdgeCrossing raw);
double expected_crossing_seconds(const EdgeCrossing& sanitized);

}  // namespace rondo::plan
