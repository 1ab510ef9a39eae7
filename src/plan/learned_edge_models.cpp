#include "rondo/plan/learned_edge_models.h"

#include <algorithm>
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

namespace {

// kLawPoints equal groups of the table's knots, each a point at the group's mean.
std::vector<DurationPoint> table_law(const learn::QuantileTable& table) {
  const std::vector<double>& knots = table.values();
  std::vector<DurationPoint> law;
  const std::size_t n = knots.size();
  const std::size_t groups = LearnedEdgeModels::kLawPoints;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t begin = n * g / groups;
    const std::size_t end = n * (g + 1) / groups;
    if (end <= begin) continue;
    double sum = 0.0;
    for (std::size_t i = begin; i < end; ++i) sum += knots[i];
    law.push_back({sum / static_cast<double>(end - begin), static_cast<double>(end - begin)});
  }
  return law;
}

// A stopped attempt becomes a third way an attempt goes, with its share c of the edge's attempts:
// it succeeds with p (1 − c) (p, the model's, is learned from ended attempts only), and an attempt
// that does not succeed is a stopped one, lasting the stopped law, with probability p c / (1 −
// p (1 − c)), else a failed one. c is taken at most kMaxStoppedShare, so an edge whose attempts
// were all stopped still leads somewhere.
void with_stopped(const StoppedAttempts& stopped, RouteLeg& leg) {
  if (!(stopped.share > 0.0) || stopped.law.empty()) return;
  const double c = std::min(stopped.share, LearnedEdgeModels::kMaxStoppedShare);
  const double p = std::clamp(leg.success_probability, 0.0, 1.0);
  const double unsuccessful = 1.0 - p * (1.0 - c);
  if (!(unsuccessful > 0.0)) return;
  const auto total = [](const std::vector<DurationPoint>& law) {
    double sum = 0.0;
    for (const DurationPoint& d : law) sum += d.weight;
    return sum;
  };
  std::vector<DurationPoint>& failure = leg.failure_law;
  if (failure.empty()) failure.push_back({leg.attempt_seconds, 1.0});
  const double failed = total(failure);
  const double cut = total(stopped.law);
  if (!(failed > 0.0) || !(cut > 0.0)) return;
  for (DurationPoint& d : failure) d.weight *= (1.0 - p) / unsuccessful / failed;
  for (const DurationPoint& d : stopped.law) failure.push_back({d.seconds, d.weight * p * c / unsuccessful / cut});
  std::erase_if(failure, [](const DurationPoint& d) { return !(d.weight > 0.0); });
  leg.success_probability = p * (1.0 - c);
}

}  // namespace

void LearnedEdgeModels::attempt_laws(map::EdgeIndex edge, Time at, RouteLeg& leg) const {
  if (!attempt_laws_) return;
  const std::size_t i = index_.at(edge);
  const learn::EpisodeEdgeModel* own = i == kUnknown ? nullptr : models_->model(i);
  const auto* tables = own ? &own->durations() : nullptr;
  const auto bin = own ? static_cast<std::size_t>(own->priors()->duration_bin(at)) : 0;
  if (tables && bin < tables->success.size() && bin < tables->failure.size()) {
    leg.success_law = table_law(tables->success[bin]);
    leg.failure_law = table_law(tables->failure[bin]);
  } else {
    for (const DurationPoint& d : attempt_laws_->success)
      leg.success_law.push_back({d.seconds * leg.attempt_seconds, d.weight});
    for (const DurationPoint& d : attempt_laws_->failure)
      leg.failure_law.push_back({d.seconds * leg.attempt_seconds, d.weight});
  }
  if (edge < attempt_laws_->stopped.size()) with_stopped(attempt_laws_->stopped[edge], leg);
}

EdgeCrossing LearnedEdgeModels::outcome(map::EdgeIndex edge, Time at) const {
  const std::size_t i = index_.at(edge);
  if (i == kUnknown) return prior_.outcome(edge, at);
  if (live_)
    return {.success_probability = live_->success_probability(i, at),
            .expected_seconds = live_->expected_seconds(i, at)};
  return {.success_probability = models_->success_probability(i, at),
          .expected_seconds = models_->expected_seconds(i, at)};
}

}  // namespace rondo::plan
