// The learned navigation models of a whole map: for every edge, the probability that crossing it
// succeeds p_e(t), its expected traversal time E[τ_e(t)] and the quantiles of τ_e(t), fitted from
// the traversal log. What plan::TravelPlanner asks.
//
//   std::vector<EdgeSpec> edges = {{"Aisle1_Aisle2", 14.0}, {"Aisle2_Aisle1", 14.0}};  // id, prior s
//   auto models = EdgeModels::fit(edges, traversals);          // shared_ptr<const EdgeModels>
//   EdgeEstimate e = *models->estimate("Aisle1_Aisle2", t, {0.5, 0.9});
//   if (auto s = models->save("models.json"); !s) ...;
//   LiveEdgeModels live(models);                                // the executor's online view
//   live.observe(traversal);  double p = live.probability(live.index_of("Aisle1_Aisle2"), t);
//
// It knows edges only as ids with a prior travel time (from the map's geometry, or 0 when unknown),
// so it does not depend on rondo::map. An edge with fewer than `min_attempts` attempts gets the
// prior model: the pooled success rate, and durations = its prior time × the pooled distribution of
// (actual / prior) time over the edges that have data (the prior time itself when no edge has both
// data and a prior; the pooled durations for an edge without a prior).
#pragma once

#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/episode_model.h"

namespace rondo::learn {

class WeeklyMemory;

struct EdgeSpec {
  std::string id;
  double prior_seconds = 0;  // distance-based travel time estimate; <= 0 when unknown
};

struct EdgeModelsOptions {
  EpisodeOptions episode;
  int min_attempts = 10;  // fewer attempts: the prior model
};

struct EdgeEstimate {
  double success_probability = 0;
  double expected_seconds = 0;
  std::vector<double> quantile_seconds;  // one per requested level, non-decreasing in the level
};

class EdgeModels {
 public:
  // Fits every edge of `edges` from the traversals whose edge_id names one of them (others are
  // ignored). Duplicate edge ids are an error.
  static Result<std::shared_ptr<const EdgeModels>> fit(std::span<const EdgeSpec> edges, std::span<const Traversal> log,
                                                       const EdgeModelsOptions& options = {});

  std::size_t size() const { return edges_.size(); }
  const EdgeSpec& spec(std::size_t index) const { return edges_[index].spec; }
  // The index of an edge id; kNotFound naming the id otherwise.
  Result<std::size_t> index_of(std::string_view edge_id) const;
  bool has_own_model(std::size_t index) const { return edges_[index].model != nullptr; }
  int attempts(std::size_t index) const { return edges_[index].attempts; }
  // The edge's own fitted model (its weekly choice, statistics); null for the prior model.
  const EpisodeEdgeModel* model(std::size_t index) const { return edges_[index].model.get(); }
  // What the fit pooled over its edges (its options among them).
  const EpisodePriors& priors() const { return *priors_; }

  // Offline estimates (not conditioned on recent outcomes). Precondition: index < size().
  double success_probability(std::size_t index, Time t) const;
  double expected_seconds(std::size_t index, Time t) const;
  double quantile_seconds(std::size_t index, Time t, double q) const;
  Result<EdgeEstimate> estimate(std::string_view edge_id, Time t, std::span<const double> levels = {}) const;

  // A copy in which every edge with a model of its own takes the live time-of-week term that
  // `memory` chooses for it under this fit's options (WeeklyMemory::choice and shift); the term
  // from the fit's own window is dropped. The rest is shared with this one.
  std::shared_ptr<const EdgeModels> with_weekly(const WeeklyMemory& memory) const;

  Json to_json() const;
  static Result<std::shared_ptr<const EdgeModels>> from_json(const Json& j);
  // JSON file; errors name the file.
  Status save(const std::filesystem::path& file) const;
  static Result<std::shared_ptr<const EdgeModels>> load(const std::filesystem::path& file);

 private:
  friend class LiveEdgeModels;
  struct Entry {
    EdgeSpec spec;
    int attempts = 0;
    std::shared_ptr<const EpisodeEdgeModel> model;  // null: the prior model
  };
  // The prior model of an edge without enough data.
  double prior_quantile(const Entry& e, double q) const;
  double prior_mean(const Entry& e) const;
  const EpisodeEdgeModel& prior_rates() const { return *prior_rates_; }

  std::shared_ptr<const EpisodePriors> priors_;
  std::shared_ptr<const EpisodeEdgeModel> prior_rates_;  // an edge with no data of its own
  QuantileTable prior_ratio_;                            // actual / prior time, pooled over edges with data and a prior
  double prior_ratio_mean_ = 1;
  bool have_ratio_ = false;
  QuantileTable pooled_durations_;
  double pooled_mean_ = 0;
  std::vector<Entry> edges_;
  std::unordered_map<std::string, std::size_t> index_;
};

// The executor's online view of a fitted model set: per-edge live statistics updated with every
// traversal (O(1)), predictions conditioned on each edge's recent outcomes. Single-threaded; the
// shared EdgeModels stays immutable. The time-of-week part of each edge's success probability is
// kept per slot of the week (EpisodeEdgeModel::slot_probabilities) from the first read after an
// update to the next update of that edge, so the planner's many reads cost little.
class LiveEdgeModels {
 public:
  explicit LiveEdgeModels(std::shared_ptr<const EdgeModels> models);
  // Records a finished traversal; traversals of unknown edges are ignored (returns false).
  bool observe(const Traversal& t);
  void observe(std::size_t index, const Attempt& a);
  double success_probability(std::size_t index, Time t) const;
  double expected_seconds(std::size_t index, Time t) const;
  double quantile_seconds(std::size_t index, Time t, double q) const;
  const EdgeModels& models() const { return *models_; }
  // The live statistics of an edge (its recency state: last_end, last_success).
  const EpisodeStats& live(std::size_t index) const { return live_[index]; }

 private:
  const EpisodeEdgeModel& rates(std::size_t index) const;
  double slot_value(std::size_t index, Time t) const;

  std::shared_ptr<const EdgeModels> models_;
  std::vector<EpisodeStats> live_;
  mutable std::vector<std::vector<double>> slots_;  // per edge; empty: not read since its last update
};

}  // namespace rondo::learn
