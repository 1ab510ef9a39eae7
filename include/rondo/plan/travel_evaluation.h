// How well do learned models predict how long journeys take? The integrated-control paper's
// Table I, on any traversal log and map: the real Witham Wharf logs (`rondo eval travel`) or a
// simulated deployment's own log (`rondo run`).
//
//   TravelEvaluationOptions o{.trainings = {{"none", t0, t0}, {"week1", t0, t0 + days(7)}},
//                             .test = {"test", split, end}};
//   TravelEvaluation result = evaluate_travel(map, log, o).value();
//   std::cout << travel_evaluation_to_table(result);            // or travel_evaluation_to_json
//
// Protocol (docs/planning.md).
// - The log is cut into journeys (journeys.h). Scored: every journey that starts in the test
//   window [from, to), ends with a success, lasts g > 0 s, and whose successful edges, origin and
//   destination are in the map. The same journeys are scored in every row.
// - For each training window [from, to) and model family, models are fitted on the attempts that
//   start in the window (an empty window: no data, each family's prior). offline: those models
//   answer for every journey. online: before a journey they also learn every attempt that starts
//   at or after the window's end and ended before the journey started (ends count as before a
//   start s when earlier than s + start_resolution, as in learn's evaluation).
// - Estimates, with every edge read at the journey's start time (as the published system does):
//   route = Σ over the journey's successful attempts, in order, of τ_e/p_e (the expected time to
//   cross e, retries included); od = the exact MDP's expected time from origin to destination.
//   Round trips (destination = origin) have no od estimate (it would be 0 s, an error of −1
//   whatever the model): od rows count only the other journeys.
//   Map edges a family does not know answer with the distance prior.
// - A fleet's log (attempts of several robots): each training window also gives the robots' paces
//   (learn::RobotSpeeds), its models are fitted on the window in the fleet's standard time, the
//   online attempts are observed in it, and a journey's estimates are its robot's (÷ its factor).
//   A lone robot's log is scored as it is.
// - Each row summarises the relative errors (estimate − g)/g over the scored journeys.
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/core/traversal.h"
#include "rondo/learn/edge_model_families.h"
#include "rondo/map/map_geometry.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/journeys.h"

namespace rondo::plan {

struct TimeWindow {
  std::string name;  // "none", "week1", "weeks1-2", "all", "test" ...
  Time from{};       // [from, to); from >= to is empty
  Time to{};
};

struct TravelEvaluationOptions {
  std::vector<TimeWindow> trainings;
  TimeWindow test;
  std::vector<learn::EdgeFamily> families = {learn::EdgeFamily::kStatic, learn::EdgeFamily::kFremen,
                                             learn::EdgeFamily::kEpisode};
  learn::EdgeFamilyOptions models{};  // its `online` is set per protocol
  JourneyRule journeys{};
  map::TravelTimeOptions travel{};  // the distance prior (edge_specs)
  Duration start_resolution = seconds(1);
};

// Quantiles (linear interpolation between order statistics), mean |x|, sample standard deviation.
struct ErrorSummary {
  double q10 = 0, q25 = 0, q75 = 0, q90 = 0, mean_abs = 0, std = 0;
  std::size_t count = 0;
};
// All zero for no values; std 0 for one. Precondition: finite values.
ErrorSummary summarize_errors(std::vector<double> values);

struct TravelErrorRow {
  std::string training;  // the window's name
  std::string model;     // learn::to_string(family)
  std::string protocol;  // "offline" | "online"
  std::string estimate;  // "route" | "od"
  ErrorSummary errors;
};

struct TravelEvaluation {
  std::size_t journeys = 0;       // scored (the count of every route row)
  std::size_t test_journeys = 0;  // starting in the test window
  std::size_t failed = 0;         // of those, ended with a failure
  std::size_t off_map = 0;        // of those, naming an edge or node not in the map
  std::size_t round_trips = 0;    // scored journeys that end where they started (no od row)
  std::vector<TravelErrorRow> rows;  // trainings × families × {offline, online} × {route, od}
};

// An error when no journey can be scored, or a training window's models cannot be fitted.
Result<TravelEvaluation> evaluate_travel(const map::TopoMap& map, std::span<const Traversal> log,
                                         const TravelEvaluationOptions& options);
// The same with the training windows read from `training_log`, and the journeys scored (and the
// attempts the online protocol observes) from `test_log`: what one deployment's first days
// teach about another's journeys (bench_fleet_learning: a lone robot against a fleet).
Result<TravelEvaluation> evaluate_travel(const map::TopoMap& map, std::span<const Traversal> training_log,
                                         std::span<const Traversal> test_log, const TravelEvaluationOptions& options);

// {"journeys": N, "test_journeys", "failed", "off_map", "round_trips", "rows": [{"training", "model", "protocol",
// "estimate", "q10", "q25", "q75", "q90", "mean_abs", "std", "count"}]}
Json travel_evaluation_to_json(const TravelEvaluation& e);
std::string travel_evaluation_to_table(const TravelEvaluation& e);

}  // namespace rondo::plan
