// Per-edge model families behind one small interface, so that one comparison can ask the same
// questions of each: static, FreMEn and rondo's episode model (EdgeModels). Used by the planner's
// travel-time evaluation (the paper's Table I, plan/travel_evaluation.h).
//
//   std::vector<EdgeSpec> specs = ...;                         // ids + distance-prior seconds
//   auto m = fit_edge_family(EdgeFamily::kFremen, specs, training).value();
//   std::size_t i = *m->index_of("Aisle1_Aisle2");
//   double crossing = m->expected_seconds(i, t) / m->success_probability(i, t);
//   m->observe(traversal);                                      // online: later answers include it
//
// Contract. index_of() knows exactly the ids of `specs`. success_probability() is in (0, 1] and
// expected_seconds() >= 0 for every known edge and time. observe() takes attempts in order of their
// end and ignores unknown edges (returns false). Families:
// - static: p = the edge's success rate, τ = its mean attempt duration (failed ones included);
//   p is floored at 0.01, the same floor FreMEn's clamp gives (so p is never 0).
// - fremen: FreMEn (fremen.h) of the success flags (clamped to [0.01, 0.99]) and of the attempt
//   durations (floored at 0), order `fremen_order`, refitted lazily after each observation.
// - episode: learn::EdgeModels (edge_models.h), its offline answers; with `online`, those of
//   LiveEdgeModels (conditioned on each edge's recent outcomes, training and observed attempts).
//   Its own priors answer for edges with little data; an edge without data in a set fitted on no
//   durations at all (where EdgeModels' pooled prior says 0 s) answers τ = prior_seconds.
// An edge without any attempt (static, fremen) answers with the distance prior: p = 1, τ = the
// spec's prior_seconds (0 when unknown). Single-threaded; not copyable.
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/edge_models.h"

namespace rondo::learn {

enum class EdgeFamily { kStatic, kFremen, kEpisode };

// "static", "fremen", "episode".
const char* to_string(EdgeFamily family);

struct EdgeFamilyOptions {
  int fremen_order = 2;           // FreMEn components kept (FremenOptions' default)
  double min_probability = 0.01;  // floor of the static model's p
  bool online = false;            // episode: answer with the online (state-conditioned) predictions
  EdgeModelsOptions episode{};
};

class FamilyEdgeModels {
 public:
  virtual ~FamilyEdgeModels() = default;
  virtual EdgeFamily family() const = 0;
  virtual std::optional<std::size_t> index_of(std::string_view edge_id) const = 0;
  // Preconditions: index from index_of().
  virtual double success_probability(std::size_t index, Time t) const = 0;
  virtual double expected_seconds(std::size_t index, Time t) const = 0;
  virtual bool observe(const Traversal& attempt) = 0;
};

// Fits one model per spec from the traversals of `training` that name a spec's id (others are
// ignored; any order). An error for duplicate or empty ids.
Result<std::unique_ptr<FamilyEdgeModels>> fit_edge_family(EdgeFamily family, std::span<const EdgeSpec> specs,
                                                          std::span<const Traversal> training,
                                                          const EdgeFamilyOptions& options = {});

}  // namespace rondo::learn
