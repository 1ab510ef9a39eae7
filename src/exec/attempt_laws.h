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
//
// Attempts stopped before they ended (the navigation monitor cut the journey while the robot was
// still on the edge) never reach the traversal log, yet they are the long ones: in the Witham
// Wharf logs an unsuccessful attempt usually ends after 170-280 s, past a short journey's limit.
// They are kept as observations (kStoppedAttempt, the edge, its start, the seconds run) and
// learn_stopped_attempts gives each edge their share of its attempts in the window
// and a law of how long they ran: a lower bound, which the monitor's limit (the quantile + slack)
// then lets the next such attempt run past, so the tail learned grows until attempts end.
#pragma once

#include <cstddef>
#include <span>

#include "rondo/core/traversal.h"
#include "rondo/learn/edge_models.h"
#include "rondo/map/topo_map.h"
#include "rondo/store/observations.h"
#include "rondo/plan/travel_time_distribution.h"

namespace rondo::exec {

plan::AttemptLaws learn_attempt_laws(const learn::EdgeModels& models, std::span<const Traversal> log,
                                     std::size_t points = 8);

// The observation kind of an edge attempt stopped before it ended: where the edge id, when the
// attempt's start, value the seconds it had run.
inline constexpr const char* kStoppedAttempt = "edge attempt stopped";

// Per map edge (by index; edges without stopped attempts get share 0): the stopped attempts'
// share of all the edge's attempts (the ended ones in `log`, the stopped ones in `stopped`) and
// the law of their seconds (`points` equal-count group means). Observations of other kinds, edges the map
// does not know and values that are not finite and positive are ignored.
std::vector<plan::StoppedAttempts> learn_stopped_attempts(const map::TopoMap& map, std::span<const Traversal> log,
                                                          std::span<const store::Observation> stopped,
                                                          std::size_t points = 4);

// A law of `points` equal-count group means of `ratios` (empty for no ratios). Sorts `ratios`.
std::vector<plan::DurationPoint> group_means(std::vector<double>& ratios, std::size_t points);

}  // namespace rondo::exec
