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
                                     const DistancePriorOptions& prior, Reading reading)
    : prior_(map, prior), reading_(reading), models_(std::move(models)) {
  edge_ids_.reserve(map.edge_count());
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) edge_ids_.push_back(map.edge(e).id);
  match();
}

void LearnedEdgeModels::match() {
  index_.assign(edge_ids_.size(), kUnknown);
  edge_version_.assign(edge_ids_.size(), 0);
  known_ = 0;
  live_.reset();
  if (!models_) return;
  if (reading_ == Reading::kOnline) live_.emplace(models_);
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
  snapshot_version_ = ++version_;
}

bool LearnedEdgeModels::observe(map::EdgeIndex edge, const learn::Attempt& attempt) {
  const std::size_t i = index_.at(edge);
  if (!live_ || i == kUnknown) return false;
  live_->observe(i, attempt);
  edge_version_[edge] = ++version_;
  return true;
}

Time LearnedEdgeModels::conditioned_until(map::EdgeIndex edge) const {
  const std::size_t i = index_.at(edge);
  if (!live_ || i == kUnknown || !live_->live(i).has_last) return Time{};
  return live_->live(i).last_end;
}

Duration LearnedEdgeModels::memory() const {
  if (!live_) return Duration{0};
  // The last gap bucket starts at 4 s x (2^(kGapBuckets - 1) - 1) (EpisodeStats::state_of); a
  // retry (within retry_gap of a failure) is shorter than that.
  return seconds(4 * ((std::int64_t{1} << (learn::kGapBuckets - 1)) - 1)) + seconds(1);
}

std::optional<std::vector<map::EdgeIndex>> LearnedEdgeModels::changed_since(std::uint64_t since) const {
  if (since < snapshot_version_) return std::nullopt;
  std::vector<map::EdgeIndex> changed;
  if (since == version_) return changed;
  for (map::EdgeIndex e = 0; e < edge_version_.size(); ++e)
    if (edge_version_[e] > since) changed.push_back(e);
  return changed;
}

EdgeOutcome LearnedEdgeModels::outcome(map::EdgeIndex edge, Time at) const {
  const std::size_t i = index_.at(edge);
  if (i == kUnknown) return prior_.outcome(edge, at);
  if (live_)
    return {.success_probability = live_->success_probability(i, at),
            .expected_seconds = live_->expected_seconds(i, at)};
  return {.success_probability = models_->success_probability(i, at),
          .expected_seconds = models_->expected_seconds(i, at)};
}

}  // namespace rondo::plan
