// `rondo plan`: the optimal navigation policy between two nodes of a map at a departure time: the
// route it takes, the expected travel time (retries included) and quantiles of the travel time.
// Without --models the edges follow the distance prior (the paper's W0); with --models, the learned
// models (plan::LearnedEdgeModels), the prior for edges they do not know.
#include <fmt/format.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "rondo/core/document.h"
#include "rondo/core/time.h"
#include "rondo/map/map_loader.h"
#include "rondo/learn/edge_models.h"
#include "rondo/plan/distance_prior.h"
#include "rondo/plan/exact_solver.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/mdp.h"
#include "rondo/plan/travel_planner.h"
#include "time_parsing_cli.h"

namespace rondo::app {
namespace {

constexpr double kQuantiles[] = {0.1, 0.25, 0.5, 0.75, 0.9};

struct PlanOptions {
  std::string map_file;
  std::string models_file;
  std::string from;
  std::string to;
  std::string at;
  std::string budget;
  double prior_probability = 1.0;
  bool json = false;
};

Result<map::NodeIndex> find_node(const map::TopoMap& m, const std::string& option, const std::string& name,
                                 const std::string& file) {
  if (auto i = m.find_node(name)) return *i;
  return Error::not_found(fmt::format("{}: no node '{}' in the map {}", option, name, file));
}

// Seconds with their readable form: "83.4 s (1m23.4s)".
std::string seconds_text(double s) {
  if (!(s < plan::kInfinity)) return "unbounded";
  return fmt::format("{:.1f} s ({})", s, format_duration(from_seconds(s)));
}

Status run_plan(CommandContext& ctx, const PlanOptions& o) {
  if (!(o.prior_probability > 0.0 && o.prior_probability <= 1.0)) {
    return Error::invalid(fmt::format("--prior-probability: must be in (0, 1], got {}", o.prior_probability));
  }
  std::optional<Time> depart;
  if (!o.at.empty()) {
    RONDO_ASSIGN_OR_RETURN(depart, parse_time_option("--at", o.at));
  }
  std::optional<double> budget;
  if (!o.budget.empty()) {
    auto d = parse_duration(o.budget);
    if (!d) return Error::invalid("--budget: " + d.error().message);
    budget = to_seconds(*d);
  }
  RONDO_ASSIGN_OR_RETURN(map::TopoMap m, map::load_map(o.map_file));
  RONDO_ASSIGN_OR_RETURN(map::NodeIndex from, find_node(m, "--from", o.from, o.map_file));
  RONDO_ASSIGN_OR_RETURN(map::NodeIndex to, find_node(m, "--to", o.to, o.map_file));

  std::shared_ptr<const learn::EdgeModels> learned;
  if (!o.models_file.empty()) {
    if (!depart) return Error::invalid("--models needs --at: learned models depend on the departure time");
    auto loaded = learn::EdgeModels::load(o.models_file);
    if (!loaded) return loaded.error().with_context("--models");
    learned = *loaded;
  }
  auto models = std::make_shared<plan::LearnedEdgeModels>(
      m, learned, plan::DistancePriorOptions{.success_probability = o.prior_probability});
  plan::TravelPlanner oracle(m, models);
  const Time at = depart.value_or(Time{});
  const plan::Policy& policy = oracle.policy(to, at);
  const std::vector<plan::PolicyStep> route = policy.route(from);
  const plan::TravelTimeDistribution distribution = policy.travel_time_distribution(from);
  const bool reachable = policy.reaches_target(from);
  const std::string models_text =
      learned ? fmt::format("learned ({}: {} of {} map edges; the others: distance prior, p = {:g})", o.models_file,
                            models->known_edge_count(), m.edge_count(), o.prior_probability)
              : fmt::format("distance prior (p = {:g} per attempt, no learned data)", o.prior_probability);

  if (o.json) {
    Json j = Json::object();
    j["map"] = o.map_file;
    j["from"] = o.from;
    j["to"] = o.to;
    j["depart"] = depart ? Json(format_time(*depart)) : Json(nullptr);
    j["models"] = learned ? "learned" : "prior";
    if (learned) {
      j["models_file"] = o.models_file;
      j["learned_edges"] = models->known_edge_count();
    }
    j["prior_probability"] = o.prior_probability;
    j["reachable"] = reachable;
    j["expected_seconds"] = reachable ? Json(policy.expected_seconds(from)) : Json(nullptr);
    Json names = Json::array();
    if (reachable) names.push_back(m.node(from).name);
    Json steps = Json::array();
    for (const plan::PolicyStep& s : route) {
      names.push_back(m.node(s.to).name);
      steps.push_back({{"edge", m.edge(s.edge).id},
                       {"from", m.node(s.from).name},
                       {"to", m.node(s.to).name},
                       {"action", m.edge(s.edge).action},
                       {"success_probability", s.success_probability},
                       {"attempt_seconds", s.attempt_seconds},
                       {"expected_seconds", s.attempt_seconds / s.success_probability}});
    }
    j["route"] = names;
    j["steps"] = steps;
    Json quantiles = Json::array();
    if (reachable) {
      for (double q : kQuantiles) {
        const plan::QuantileBounds b = distribution.quantile(q);
        quantiles.push_back(
            {{"q", q}, {"lower", b.lower}, {"upper", b.upper < plan::kInfinity ? Json(b.upper) : Json(nullptr)}});
      }
    }
    j["quantiles"] = quantiles;
    if (budget) {
      const plan::ProbabilityBounds p = distribution.probability_within(*budget);
      j["budget_seconds"] = *budget;
      j["probability_within_budget"] = {{"lower", p.lower}, {"upper", p.upper}};
    }
    ctx.out << j.dump(2, ' ', false, Json::error_handler_t::replace) << '\n';
  } else {
    auto row = [&](std::string_view label, const std::string& value) {
      ctx.out << fmt::format("{:<11}{}\n", label, value);
    };
    row("map", fmt::format("{} ({} nodes, {} edges)", o.map_file, m.node_count(), m.edge_count()));
    row("from", o.from);
    row("to", o.to);
    row("depart", depart ? format_time(*depart) : std::string("any time (the prior does not depend on it)"));
    row("models", models_text);
    if (!reachable) {
      row("route", fmt::format("none: '{}' cannot reach '{}'", o.from, o.to));
    } else {
      std::string names = m.node(from).name;
      for (const plan::PolicyStep& s : route) names += " -> " + m.node(s.to).name;
      row("route", fmt::format("{} ({} edge{})", names, route.size(), route.size() == 1 ? "" : "s"));
      row("expected", seconds_text(policy.expected_seconds(from)));
      std::vector<std::string> qs;
      for (double q : kQuantiles) qs.push_back(fmt::format("q{:g} {:.1f}", q * 100, distribution.quantile(q).upper));
      row("quantiles", fmt::format("{} s (upper bounds, docs/planning.md)", fmt::join(qs, ", ")));
      if (budget) {
        const plan::ProbabilityBounds p = distribution.probability_within(*budget);
        row("on time", fmt::format("P(arrive within {:.1f} s) in [{:.4f}, {:.4f}]", *budget, p.lower, p.upper));
      }
      for (const plan::PolicyStep& s : route) {
        row("", fmt::format("{} -> {}  {}  p {:.2f}  attempt {:.1f} s  expected {:.1f} s", m.node(s.from).name,
                            m.node(s.to).name, m.edge(s.edge).action, s.success_probability, s.attempt_seconds,
                            s.attempt_seconds / s.success_probability));
      }
    }
  }
  if (!reachable) {
    ctx.err << fmt::format("rondo: '{}' cannot reach '{}' in {}\n", o.from, o.to, o.map_file);
    ctx.exit_code = 1;
  }
  return {};
}

}  // namespace

void add_plan_commands(CLI::App& root, CommandContext& ctx) {
  auto opts = std::make_shared<PlanOptions>();
  CLI::App* cmd = root.add_subcommand(
      "plan", "The optimal route between two nodes: expected travel time (retries included) and its quantiles");
  cmd->add_option("--map", opts->map_file, "Map file: rondo .yaml, STRANDS .tmap, .yaml or .json")->required();
  cmd->add_option("--models", opts->models_file,
                  "Learned edge models (JSON from 'rondo learn'); edges they lack follow the distance prior");
  cmd->add_option("--from", opts->from, "Start node name")->required();
  cmd->add_option("--to", opts->to, "Target node name")->required();
  cmd->add_option("--at", opts->at, "Departure time, ISO 8601 with a zone (e.g. 2014-09-02T16:24:00Z)");
  cmd->add_option("--budget", opts->budget,
                  "Also print the probability of arriving within this duration (e.g. 90s, 2m)");
  cmd->add_option("--prior-probability", opts->prior_probability,
                  "Success probability of every attempt under the distance prior, in (0, 1]")
      ->default_val(1.0);
  cmd->add_flag("--json", opts->json, "Print JSON instead of a table");
  cmd->callback([&ctx, opts] {
    if (Status s = run_plan(ctx, *opts); !s) fail(ctx, s.error());
  });
}

}  // namespace rondo::app
