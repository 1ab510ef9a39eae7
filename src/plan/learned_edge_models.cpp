#include "rondo/plan/learned_edge_models.h"

#include <utility>

namespace rondo::plan {

std::vector<learn::EdgeSpec> edge_specs(const map::TopoMap& map, const map::TravelTimeOptions& travel) {
  std::vector<learn::EdgeSpec> specs;
  specs.reserve(map.edge_count());
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) {
    specs.push_back({.id = map.edge(e).id, .prior_seconds = to_seconds(map::nominal_travel_time(map, e, travel))});
  }
  return specs;
}

LearnedEdgeModels::LearnedEdgeModels(const map::TopoMap& map, std::shared_ptr<const learn::EdgeModels> models,
                                     const DistancePriorOptions& prior)
    : prior_(map, prior), models_(std::move(models)) {
  edge_ids_.reserve(map.edge_count());
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) edge_ids_.push_back(map.edge(e).id);
  match();
}

void LearnedEdgeModels::match() {
  index_.assign(edge_ids_.size(), kUnknown);
  known_ = 0;
  if (!models_) return;
  for (std::size_t e = 0; e < edge_ids_.size(); ++e) {
    if (auto i = models_->index_of(edge_ids_[e])) {
      index_[e] = *i;
      ++known_;
    }
  }
}

void LearnedEdgeModels::set(std::shared_ptr<const learn::EdgeModels> models) {
  models_ = std::move(models);
  match();
  ++version_;
}

EdgeOutcome LearnedEdgeModels::outcome(map::EdgeIndex edge, Time at) const {
  const std::size_t i = index_.at(edge);
  if (i == kUnknown) return prior_.outcome(edge, at);
  return {.success_probability = models_->success_probability(i, at),
          .expected_seconds = models_->expected_seconds(i, at)};
}

}  // namespace rondo::plan
