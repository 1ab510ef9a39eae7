// The pooled attempt-duration laws of the travel-time distribution (plan::AttemptLaws), for edges
// without a fitted model of their own (those use their own duration tables, LearnedEdgeModels::
// attempt_laws), learned from the traversal log at refit time under risk_alpha: every attempt's duration divided by its edge's expected attempt
// seconds at its start (the fitted models'), pooled over all edges, separately for successful and
// failed attempts, and cut into `points` groups of equal count, each group a point at its mean
// with weight 1/points (so each law keeps the sample's mean).
//
//   auto fitted = learn::EdgeModels::fit(specs, log).value();
//   plan::AttemptLaws laws = learn_attempt_laws(*fitted, log);
//
// A law with no attempts behind it stays empty (the distribution then uses the expected seconds).
#pragma once

#include <cstddef>
#include <span>

#include "rondo/core/traversal.h"
#include "rondo/learn/edge_models.h"
#include "rondo/plan/travel_time_distribution.h"

namespace rondo::exec {

plan::AttemptLaws learn_attempt_laws(const learn::EdgeModels& models, std::span<const Traversal> log,
                                     std::size_t points = 8);

// A law of `points` equal-count group means of `ratios` (empty for no ratios). Sorts `ratios`.
std::vector<plan::DurationPoint> group_means(std::vector<double>& ratios, std::size_t points);

}  // namespace rondo::exec
