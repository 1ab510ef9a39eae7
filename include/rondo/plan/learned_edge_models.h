// The learned edge models (rondo::learn::EdgeModels) seen through the planner's EdgeModelView, and
// the edge list a map gives the learner. This is how a refit reaches the planner:
//
//   std::vector<learn::EdgeSpec> specs = edge_specs(map);          // id + distance prior seconds
//   auto fitted = learn::EdgeModels::fit(specs, traversals).value();
//   auto models = std::make_shared<LearnedEdgeModels>(map, fitted);
//   TravelPlanner oracle(map, models);                               // reads models->outcome()
//   models->set(refitted);                                          // version() moves on: the
//                                                                   // oracle drops its caches
//   LearnedEdgeModels live(map, fitted, {}, Reading::kOnline);      // the executor's: online
//   live.observe(edge, attempt);   // that edge only: changed_since() lists it, caches keep the rest
//
// Contract. Map edge e is matched to the model set by its id, once per set(). An edge the model
// set does not know (or every edge, while the set is null) answers with DistancePrior. A known
// edge answers {success_probability(i, t), expected_seconds(i, t)} of the offline models: for an
// edge with too little data of its own that is learn's prior model (pooled rate, prior time ×
// pooled ratio; with no durations at all, the edge's prior time), see edge_models.h.
//
// Online reading (Reading::kOnline): the answers are learn::LiveEdgeModels', the online protocol
// of `rondo eval` (docs/learning.md, Table I): each edge's snapshot statistics updated with every
// attempt observe()d since the snapshot, and its success probability conditioned on the outcome of
// its last attempt and the time since (so a closure is believed at once and forgotten as the gap
// grows, a failure of a minute ago weighs more than one of an hour ago). set() starts again from
// the new snapshot's own statistics (which include its log up to the refit).
// outcome() is const and pure for a given version(); set() is
// not synchronised with it: call both from the thread that owns the oracle. The map is not kept.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
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
  enum class Reading { kOffline, kOnline };

  // `models` may be null (prior only until set()). `prior` answers for edges the models lack.
  LearnedEdgeModels(const map::TopoMap& map, std::shared_ptr<const learn::EdgeModels> models,
                    const DistancePriorOptions& prior = {}, Reading reading = Reading::kOffline);

  // Precondition: edge < the map's edge_count().
  EdgeCrossing outcome(map::EdgeIndex edge, Time at) const override;
  std::uint64_t version() const override { return version_; }

  // Online: the end of the edge's last attempt (observed or in the snapshot's log), and the gap
  // after which the recency state no longer changes (learn::kGapBuckets). Offline: the defaults.
  Time conditioned_until(map::EdgeIndex edge) const override;
  Duration memory() const override;
  // The edges observe()d since `since` when no set() came after it; nullopt otherwise.
  std::optional<std::vector<map::EdgeIndex>> changed_since(std::uint64_t since) const override;

  // With laws set: an edge with its own model gets its own duration tables of the time-of-day bin
  // of `at` (kLawPoints points each, the means of equal groups of the tables' knots); any other
  // edge the pooled laws scaled by leg.attempt_seconds. An edge with stopped attempts
  // (AttemptLaws::stopped) then has them as a third way an attempt goes: its success probability
  // is lowered by their share (at most kMaxStoppedShare) and its failure law holds them. Without
  // laws: nothing.
  void attempt_laws(map::EdgeIndex edge, Time at, RouteLeg& leg) const override;
  static constexpr double kMaxStoppedShare = 0.5;
  // The pooled attempt-duration laws (null: no laws at all). Takes effect for caches with the next
  // set(), which moves version() on: call it just before set().
  void set_attempt_laws(std::shared_ptr<const AttemptLaws> laws) { attempt_laws_ = std::move(laws); }
  static constexpr std::size_t kLawPoints = 7;

  // Swaps the snapshot (null: prior only), re-matches the edges and moves version() on.
  void set(std::shared_ptr<const learn::EdgeModels> models);

  // Online reading: learns from one attempt on map edge `edge` (a succeeded or failed one: learning
  // data, exec::is_learning_data), in the order attempts end. Only that edge's answers change;
  // version() moves on and changed_since() names it. False (nothing changes) when offline or when
  // the snapshot does not know the edge (the prior answers for it). Precondition: edge < the map's
  // edge_count().
  bool observe(map::EdgeIndex edge, const learn::Attempt& attempt);
  Reading reading() const { return reading_; }

  const std::shared_ptr<const learn::EdgeModels>& models() const { return models_; }
  // The model set's index of a map edge, or kUnknown when the prior answers for it.
  std::size_t model_index(map::EdgeIndex edge) const { return index_.at(edge); }
  // How many map edges the current model set knows.
  std::size_t known_edge_count() const { return known_; }

 private:
  void match();

  DistancePrior prior_;
  Reading reading_;
  std::vector<std::string> edge_ids_;  // of the map, by edge index
  std::shared_ptr<const learn::EdgeModels> models_;
  std::shared_ptr<const AttemptLaws> attempt_laws_;
  std::optional<learn::LiveEdgeModels> live_;  // online reading with a snapshot
  std::uint64_t snapshot_version_ = 1;         // version() of the last set()
  std::vector<std::uint64_t> edge_version_;    // per map edge: version() of its last observe()
  std::vector<std::size_t> index_;
  std::size_t known_ = 0;
  std::uint64_t version_ = 1;  // DistancePrior is 0: a fresh view never looks like the prior
};

}  // namespace rondo::plan
