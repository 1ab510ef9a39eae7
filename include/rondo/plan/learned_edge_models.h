// The learned edge models (rondo::learn::EdgeModels) seen through the planner's EdgeModelView, and
// the edge list a map gives the learner. This is how a refit reaches the planner:
//
//   std::vector<learn::EdgeSpec> specs = edge_specs(map);          // id + distance prior seconds
//   auto fitted = learn::EdgeModels::fit(specs, traversals).value();
//   auto models = std::make_shared<LearnedEdgeModels>(map, fitted);
//   TravelOracle oracle(map, models);                               // reads models->outcome()
//   models->set(refitted);                                          // version() moves on: the
//                                                                   // oracle drops its caches
//
// Contract. Map edge e is matched to the model set by its id, once per set(). An edge the model
// set does not know (or every edge, while the set is null) answers with DistancePrior. A known
// edge answers {success_probability(i, t), expected_seconds(i, t)} of the offline models: for an
// edge with too little data of its own that is learn's prior model (pooled rate, prior time ×
// pooled ratio; with no durations at all, the edge's prior time), see edge_models.h.
// outcome() is const and pure for a given version(); set() is
// not synchronised with it: call both from the thread that owns the oracle. The map is not kept.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rondo/learn/edge_models.h"
#include "rondo/map/map_geometry.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/plan/edge_model_view.h"

namespace rondo::plan {

// One learn::EdgeSpec per map edge, in edge-index order: the edge id and its distance-prior
// seconds (map::nominal_travel_time with `travel`).
std::vector<learn::EdgeSpec> edge_specs(const map::TopoMap& map, const map::TravelTimeOptions& travel = {});

class LearnedEdgeModels final : public EdgeModelView {
 public:
  static constexpr std::size_t kUnknown = static_cast<std::size_t>(-1);

  // `models` may be null (prior only until set()). `prior` answers for edges the models lack.
  LearnedEdgeModels(const map::TopoMap& map, std::shared_ptr<const learn::EdgeModels> models,
                    const DistancePriorOptions& prior = {});

  // Precondition: edge < the map's edge_count().
  EdgeOutcome outcome(map::EdgeIndex edge, Time at) const override;
  std::uint64_t version() const override { return version_; }

  // Swaps the snapshot (null: prior only), re-matches the edges and moves version() on.
  void set(std::shared_ptr<const learn::EdgeModels> models);

  const std::shared_ptr<const learn::EdgeModels>& models() const { return models_; }
  // The model set's index of a map edge, or kUnknown when the prior answers for it.
  std::size_t model_index(map::EdgeIndex edge) const { return index_.at(edge); }
  // How many map edges the current model set knows.
  std::size_t known_edge_count() const { return known_; }

 private:
  void match();

  DistancePrior prior_;
  std::vector<std::string> edge_ids_;  // of the map, by edge index
  std::shared_ptr<const learn::EdgeModels> models_;
  std::vector<std::size_t> index_;
  std::size_t known_ = 0;
  std::uint64_t version_ = 1;  // DistancePrior is 0: a fresh view never looks like the prior
};

}  // namespace rondo::plan
