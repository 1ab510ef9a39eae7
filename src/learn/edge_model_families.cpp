#include "rondo/learn/edge_model_families.h"

#include <algorithm>
#include <string>
#include <unordered_map>
#include <vector>

#include "rondo/learn/fremen.h"

namespace rondo::learn {
namespace {

// Id -> index, shared by the static and FreMEn sets.
class EdgeIndex {
 public:
  static Result<EdgeIndex> build(std::span<const EdgeSpec> specs) {
    EdgeIndex out;
    for (const EdgeSpec& s : specs) {
      if (s.id.empty()) return Error::invalid("edge models: an edge has an empty id");
      if (!out.index_.emplace(s.id, out.index_.size()).second) {
        return Error::invalid("edge models: edge '" + s.id + "' is listed twice");
      }
    }
    return out;
  }
  std::optional<std::size_t> find(std::string_view id) const {
    auto it = index_.find(std::string(id));
    if (it == index_.end()) return std::nullopt;
    return it->second;
  }

 private:
  std::unordered_map<std::string, std::size_t> index_;
};

// The training attempts of each spec, in start order.
std::vector<std::vector<const Traversal*>> per_edge(const EdgeIndex& index, std::size_t n,
                                                    std::span<const Traversal> training) {
  std::vector<std::vector<const Traversal*>> out(n);
  for (const Traversal& t : training) {
    if (auto i = index.find(t.edge_id)) out[*i].push_back(&t);
  }
  for (auto& v : out) {
    std::stable_sort(v.begin(), v.end(), [](const Traversal* a, const Traversal* b) { return a->start < b->start; });
  }
  return out;
}

class StaticSet final : public FamilyEdgeModels {
 public:
  StaticSet(EdgeIndex index, std::span<const EdgeSpec> specs, std::span<const Traversal> training, double floor)
      : index_(std::move(index)), floor_(floor) {
    for (const EdgeSpec& s : specs) edges_.push_back({.prior_seconds = std::max(0.0, s.prior_seconds)});
    for (const Traversal& t : training) observe(t);
  }
  EdgeFamily family() const override { return EdgeFamily::kStatic; }
  std::optional<std::size_t> index_of(std::string_view id) const override { return index_.find(id); }
  double success_probability(std::size_t i, Time) const override {
    const Edge& e = edges_[i];
    return e.n > 0 ? std::max(floor_, e.successes / e.n) : 1.0;
  }
  double expected_seconds(std::size_t i, Time) const override {
    const Edge& e = edges_[i];
    return e.n > 0 ? e.seconds / e.n : e.prior_seconds;
  }
  bool observe(const Traversal& t) override {
    auto i = index_.find(t.edge_id);
    if (!i) return false;
    Edge& e = edges_[*i];
    e.n += 1;
    e.successes += t.success ? 1.0 : 0.0;
    e.seconds += std::max(0.0, to_seconds(t.duration));
    return true;
  }

 private:
  struct Edge {
    double prior_seconds = 0;
    double n = 0, successes = 0, seconds = 0;
  };
  EdgeIndex index_;
  double floor_;
  std::vector<Edge> edges_;
};

class FremenSet final : public FamilyEdgeModels {
 public:
  FremenSet(EdgeIndex index, std::span<const EdgeSpec> specs, std::span<const Traversal> training, int order)
      : index_(std::move(index)), order_(order) {
    edges_.resize(specs.size());
    for (std::size_t i = 0; i < specs.size(); ++i) edges_[i].prior_seconds = std::max(0.0, specs[i].prior_seconds);
    const auto lists = per_edge(index_, specs.size(), training);  // FremenSpectrum wants time order
    for (std::size_t i = 0; i < lists.size(); ++i) {
      for (const Traversal* t : lists[i]) add(edges_[i], *t);
    }
  }
  EdgeFamily family() const override { return EdgeFamily::kFremen; }
  std::optional<std::size_t> index_of(std::string_view id) const override { return index_.find(id); }
  double success_probability(std::size_t i, Time t) const override {
    const Edge& e = solved(i);
    if (e.flags.count() == 0) return 1.0;
    return std::clamp(static_cast<double>(e.flag_model.raw_estimate(fremen_seconds(t))), 0.01, 0.99);
  }
  double expected_seconds(std::size_t i, Time t) const override {
    const Edge& e = solved(i);
    if (e.durations.count() == 0) return e.prior_seconds;
    return std::max(0.0, static_cast<double>(e.duration_model.raw_estimate(fremen_seconds(t))));
  }
  bool observe(const Traversal& t) override {
    auto i = index_.find(t.edge_id);
    if (!i) return false;
    add(edges_[*i], t);
    return true;
  }

 private:
  struct Edge {
    double prior_seconds = 0;
    FremenSpectrum flags, durations;
    FremenComponents flag_model, duration_model;
    bool dirty = true;
  };
  static void add(Edge& e, const Traversal& t) {
    const std::uint32_t s = fremen_seconds(t.start);
    e.flags.add(s, t.success ? 1.0f : 0.0f);
    e.durations.add(s, static_cast<float>(std::max(0.0, to_seconds(t.duration))));
    e.dirty = true;
  }
  const Edge& solved(std::size_t i) const {
    Edge& e = edges_[i];
    if (e.dirty) {
      e.flag_model = e.flags.solve(order_);
      e.duration_model = e.durations.solve(order_);
      e.dirty = false;
    }
    return e;
  }
  EdgeIndex index_;
  int order_;
  mutable std::vector<Edge> edges_;  // solved lazily
};

class EpisodeSet final : public FamilyEdgeModels {
 public:
  EpisodeSet(std::shared_ptr<const EdgeModels> models, bool online)
      : models_(models), live_(std::move(models)), online_(online) {}
  EdgeFamily family() const override { return EdgeFamily::kEpisode; }
  std::optional<std::size_t> index_of(std::string_view id) const override {
    auto i = models_->index_of(id);
    if (!i) return std::nullopt;
    return *i;
  }
  // Online: conditioned on the live statistics (training plus everything observed since).
  double success_probability(std::size_t i, Time t) const override {
    return online_ ? live_.success_probability(i, t) : models_->success_probability(i, t);
  }
  double expected_seconds(std::size_t i, Time t) const override {
    return online_ ? live_.expected_seconds(i, t) : models_->expected_seconds(i, t);
  }
  bool observe(const Traversal& t) override { return live_.observe(t); }

 private:
  std::shared_ptr<const EdgeModels> models_;
  LiveEdgeModels live_;
  bool online_;
};

}  // namespace

const char* to_string(EdgeFamily family) {
  switch (family) {
    case EdgeFamily::kStatic:
      return "static";
    case EdgeFamily::kFremen:
      return "fremen";
    case EdgeFamily::kEpisode:
      return "episode";
  }
  return "unknown";
}

Result<std::unique_ptr<FamilyEdgeModels>> fit_edge_family(EdgeFamily family, std::span<const EdgeSpec> specs,
                                                          std::span<const Traversal> training,
                                                          const EdgeFamilyOptions& options) {
  if (family == EdgeFamily::kEpisode) {
    auto models = EdgeModels::fit(specs, training, options.episode);
    if (!models) return models.error();
    return std::unique_ptr<FamilyEdgeModels>(std::make_unique<EpisodeSet>(std::move(*models), options.online));
  }
  auto index = EdgeIndex::build(specs);
  if (!index) return index.error();
  if (family == EdgeFamily::kStatic) {
    return std::unique_ptr<FamilyEdgeModels>(
        std::make_unique<StaticSet>(std::move(*index), specs, training, options.min_probability));
  }
  return std::unique_ptr<FamilyEdgeModels>(
      std::make_unique<FremenSet>(std::move(*index), specs, training, options.fremen_order));
}

}  // namespace rondo::learn
