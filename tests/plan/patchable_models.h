// An EdgeModelView whose edges change one at a time and which says which (changed_since), as the
// online LearnedEdgeModels does: for the properties of the caches that keep what an update does
// not touch (plan::TravelPlanner, exec::TravelCache).
//
//   PatchableEdgeModels models(map.edge_count(), [](map::EdgeIndex e, Time t) { ... });
//   models.change(3, 0.5, 2.0);   // edge 3: p x 0.5, τ x 2 from now on; changed_since names it
//   models.change_all(0.9, 1.1);  // every edge: changed_since says "anything" (nullopt)
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "rondo/plan/edge_model_view.h"

namespace rondo::plan::testing {

class PatchableEdgeModels final : public EdgeModelView {
 public:
  PatchableEdgeModels(std::size_t edges, FunctionEdgeModels::Function base)
      : base_(std::move(base)), factors_(edges, {1.0, 1.0}), edge_version_(edges, 0) {}

  EdgeCrossing outcome(map::EdgeIndex edge, Time at) const override {
    EdgeCrossing o = base_(edge, at);
    o.success_probability *= factors_[edge].first;
    o.expected_seconds *= factors_[edge].second;
    return o;
  }
  std::uint64_t version() const override { return version_; }
  std::optional<std::vector<map::EdgeIndex>> changed_since(std::uint64_t since) const override {
    if (since < snapshot_version_) return std::nullopt;
    std::vector<map::EdgeIndex> out;
    for (map::EdgeIndex e = 0; e < edge_version_.size(); ++e)
      if (edge_version_[e] > since) out.push_back(e);
    return out;
  }

  void change(map::EdgeIndex edge, double p_factor, double tau_factor) {
    factors_[edge] = {p_factor, tau_factor};
    edge_version_[edge] = ++version_;
  }
  void change_all(double p_factor, double tau_factor) {
    for (auto& f : factors_) f = {p_factor, tau_factor};
    snapshot_version_ = ++version_;
  }

 private:
  FunctionEdgeModels::Function base_;
  std::vector<std::pair<double, double>> factors_;
  std::vector<std::uint64_t> edge_version_;
  std::uint64_t version_ = 1, snapshot_version_ = 1;
};

}  // namespace rondo::plan::testing
