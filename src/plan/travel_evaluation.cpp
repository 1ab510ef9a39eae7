#include "rondo/plan/travel_evaluation.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

#include <fmt/format.h>

#include "rondo/learn/robot_speeds.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/mdp.h"

namespace rondo::plan {
namespace {

// A journey ready to score: its map edges (successful attempts, in order) and end nodes.
struct ScoredJourney {
  Time start{};
  double seconds = 0;
  std::vector<EdgeIndex> route;
  NodeIndex origin = 0;
  NodeIndex destination = 0;
  std::string robot;  // who made it (Traversal::robot)
};

struct Context {
  const map::TopoMap* map;
  std::span<const Traversal> log;
  std::vector<ScoredJourney> journeys;     // by start
  std::vector<std::size_t> by_end;         // log indices by end time
  std::vector<learn::EdgeSpec> specs;      // one per map edge
  DistancePrior prior;
  const TravelEvaluationOptions* options;
  std::shared_ptr<const DeadEnds> dead_ends;  // the map's, shared by every journey's M_t
};

// The journeys of the test window that can be scored, with the counts of those that cannot.
void select_journeys(Context& c, TravelEvaluation& out) {
  const TimeWindow& test = c.options->test;
  for (const Journey& j : cut_journeys(c.log, c.options->journeys)) {
    if (j.start < test.from || j.start >= test.to) continue;
    ++out.test_journeys;
    if (!j.succeeded || !(j.seconds() > 0)) {
      ++out.failed;
      continue;
    }
    ScoredJourney s;
    s.start = j.start;
    s.seconds = j.seconds();
    s.robot = c.log[j.attempts.front()].robot;
    bool on_map = true;
    for (std::size_t a : j.attempts) {
      if (!c.log[a].success) continue;
      const auto e = c.map->find_edge(c.log[a].edge_id);
      on_map = on_map && e.has_value();
      if (e) s.route.push_back(*e);
    }
    const auto origin = c.map->find_node(j.origin);
    const auto destination = c.map->find_node(j.destination);
    if (!on_map || !origin || !destination) {
      ++out.off_map;
      continue;
    }
    s.origin = *origin;
    s.destination = *destination;
    if (s.origin == s.destination) ++out.round_trips;
    c.journeys.push_back(std::move(s));
  }
}

// Every map edge's outcome at t under `models` (the prior for edges it does not know).
std::vector<EdgeCrossing> outcomes_at(const Context& c, const learn::FamilyEdgeModels& models,
                                     const std::vector<std::optional<std::size_t>>& index, Time t) {
  std::vector<EdgeCrossing> out;
  out.reserve(index.size());
  for (EdgeIndex e = 0; e < index.size(); ++e) {
    if (!index[e]) {
      out.push_back(c.prior.outcome(e, t));
    } else {
      out.push_back({.success_probability = models.success_probability(*index[e], t),
                     .expected_seconds = models.expected_seconds(*index[e], t)});
    }
  }
  return out;
}

struct Errors {
  std::vector<double> route, od;
};

// Scores one fitted model set, fitted in the standard time of `speeds`; `online` also feeds it the
// attempts after the training window (in standard time). Each journey's estimate is its robot's.
Result<Errors> score(const Context& c, learn::FamilyEdgeModels& models, const learn::RobotSpeeds& speeds, bool online,
                     const TimeWindow& training) {
  std::vector<std::optional<std::size_t>> index;
  for (const auto& s : c.specs) index.push_back(models.index_of(s.id));
  Errors out;
  std::size_t next = 0;  // into by_end
  for (const ScoredJourney& j : c.journeys) {
    for (; online && next < c.by_end.size(); ++next) {
      const Traversal& a = c.log[c.by_end[next]];
      if (!(a.start + a.duration < j.start + c.options->start_resolution)) break;
      if (a.start < training.to) continue;
      models.observe(speeds.standardised(a));
    }
    const double pace = speeds.factor(j.robot);
    RONDO_ASSIGN_OR_RETURN(Mdp mdp,
                           Mdp::from_outcomes(*c.map, outcomes_at(c, models, index, j.start), j.start, c.dead_ends));
    double route = 0;
    for (EdgeIndex e : j.route) route += mdp.expected_crossing_seconds(e);
    route /= pace;
    // Unusable edges give +inf; keep the summaries finite and say so through a huge error.
    out.route.push_back(std::isfinite(route) ? (route - j.seconds) / j.seconds : 1e9);
    if (j.origin == j.destination) continue;
    RONDO_ASSIGN_OR_RETURN(Solution s, ExactSolver{}.solve(mdp, j.destination));
    const double od = s.policy.expected_seconds(j.origin) / pace;
    out.od.push_back(std::isfinite(od) ? (od - j.seconds) / j.seconds : 1e9);
  }
  return out;
}

std::vector<Traversal> in_window(std::span<const Traversal> log, const TimeWindow& w) {
  std::vector<Traversal> out;
  for (const Traversal& t : log)
    if (t.start >= w.from && t.start < w.to) out.push_back(t);
  return out;
}

}  // namespace

ErrorSummary summarize_errors(std::vector<double> v) {
  ErrorSummary s;
  s.count = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  auto quantile = [&](double q) {
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto lo = static_cast<std::size_t>(std::floor(pos));
    const std::size_t hi = std::min(lo + 1, v.size() - 1);
    return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
  };
  s.q10 = quantile(0.1);
  s.q25 = quantile(0.25);
  s.q75 = quantile(0.75);
  s.q90 = quantile(0.9);
  const double n = static_cast<double>(v.size());
  const double mean = std::accumulate(v.begin(), v.end(), 0.0) / n;
  double abs_sum = 0, squares = 0;
  for (double x : v) {
    abs_sum += std::abs(x);
    squares += (x - mean) * (x - mean);
  }
  s.mean_abs = abs_sum / n;
  s.std = v.size() > 1 ? std::sqrt(squares / (n - 1)) : 0.0;
  return s;
}

Result<TravelEvaluation> evaluate_travel(const map::TopoMap& map, std::span<const Traversal> log,
                                         const TravelEvaluationOptions& options) {
  return evaluate_travel(map, log, log, options);
}

Result<TravelEvaluation> evaluate_travel(const map::TopoMap& map, std::span<const Traversal> training_log,
                                         std::span<const Traversal> log, const TravelEvaluationOptions& options) {
  Context c{.map = &map,
            .log = log,
            .journeys = {},
            .by_end = {},
            .specs = edge_specs(map, options.travel),
            .prior = DistancePrior(map, {.success_probability = 1.0, .travel = options.travel}),
            .options = &options,
            .dead_ends = std::make_shared<const DeadEnds>(DeadEnds::find(map))};
  TravelEvaluation out;
  select_journeys(c, out);
  out.journeys = c.journeys.size();
  if (c.journeys.empty()) {
    return Error::invalid(fmt::format("travel evaluation: no journey in the test window '{}' [{}, {}) can be scored "
                                      "({} start there, {} failed, {} off the map)",
                                      options.test.name, format_time(options.test.from),
                                      format_time(options.test.to), out.test_journeys, out.failed, out.off_map));
  }
  c.by_end.resize(log.size());
  std::iota(c.by_end.begin(), c.by_end.end(), std::size_t{0});
  std::stable_sort(c.by_end.begin(), c.by_end.end(), [&](std::size_t a, std::size_t b) {
    return log[a].start + log[a].duration < log[b].start + log[b].duration;
  });
  for (const TimeWindow& training : options.trainings) {
    // The robots' paces from the window, and the window's log in the fleet's standard time (a lone
    // robot's: as it is).
    std::vector<Traversal> train = in_window(training_log, training);
    const learn::RobotSpeeds speeds = learn::RobotSpeeds::fit(train);
    if (!speeds.factors().empty()) train = speeds.standardised(train);
    for (learn::EdgeFamily family : options.families) {
      for (const bool online : {false, true}) {
        learn::EdgeFamilyOptions mo = options.models;
        mo.online = online;
        auto models = learn::fit_edge_family(family, c.specs, train, mo);
        if (!models) return models.error().with_context("training window '" + training.name + "'");
        RONDO_ASSIGN_OR_RETURN(Errors e, score(c, **models, speeds, online, training));
        const std::string protocol = online ? "online" : "offline";
        out.rows.push_back({training.name, learn::to_string(family), protocol, "route", summarize_errors(e.route)});
        out.rows.push_back({training.name, learn::to_string(family), protocol, "od", summarize_errors(e.od)});
      }
    }
  }
  return out;
}

Json travel_evaluation_to_json(const TravelEvaluation& e) {
  Json rows = Json::array();
  for (const TravelErrorRow& r : e.rows) {
    rows.push_back({{"training", r.training},
                    {"model", r.model},
                    {"protocol", r.protocol},
                    {"estimate", r.estimate},
                    {"q10", r.errors.q10},
                    {"q25", r.errors.q25},
                    {"q75", r.errors.q75},
                    {"q90", r.errors.q90},
                    {"mean_abs", r.errors.mean_abs},
                    {"std", r.errors.std},
                    {"count", r.errors.count}});
  }
  return {{"journeys", e.journeys},
          {"test_journeys", e.test_journeys},
          {"failed", e.failed},
          {"off_map", e.off_map},
          {"round_trips", e.round_trips},
          {"rows", rows}};
}

std::string travel_evaluation_to_table(const TravelEvaluation& e) {
  std::string out = fmt::format(
      "{} journeys scored ({} start in the test window, {} ended in a failure, {} off the map); "
      "{} round trips have no od estimate\n"
      "relative error (estimate - truth) / truth\n",
      e.journeys, e.test_journeys, e.failed, e.off_map, e.round_trips);
  out += fmt::format("{:<10} {:<8} {:<8} {:<6} {:>8} {:>8} {:>8} {:>8} {:>9} {:>8} {:>6}\n", "training", "model",
                     "protocol", "est.", "q10", "q25", "q75", "q90", "mean|e|", "std", "count");
  for (const TravelErrorRow& r : e.rows) {
    const ErrorSummary& s = r.errors;
    out += fmt::format("{:<10} {:<8} {:<8} {:<6} {:>8.3f} {:>8.3f} {:>8.3f} {:>8.3f} {:>9.3f} {:>8.3f} {:>6}\n",
                       r.training, r.model, r.protocol, r.estimate, s.q10, s.q25, s.q75, s.q90, s.mean_abs, s.std,
                       s.count);
  }
  return out;
}

}  // namespace rondo::plan
