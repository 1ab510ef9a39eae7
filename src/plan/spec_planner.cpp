#include "rondo/plan/spec_planner.h"

#include <fmt/format.h>

#include <utility>

#include "rondo/core/utf8.h"

namespace rondo::plan {

Result<SpecPlanner> SpecPlanner::create(const map::TopoMap& map, std::shared_ptr<const EdgeModelView> models,
                                        std::shared_ptr<const ltl::Automaton> automaton,
                                        const SpecPlannerOptions& options) {
  if (!models || !automaton) return Error::invalid("a spec planner needs edge models and an automaton");
  for (const std::string& node : automaton->nodes())
    if (!map.find_node(node))
      return Error::not_found(fmt::format("the formula names node '{}', which map '{}' does not have",
                                          quote_for_message(node), quote_for_message(map.name())));
  return SpecPlanner(map, std::move(models), std::move(automaton), options);
}

SpecPlanner::SpecPlanner(const map::TopoMap& map, std::shared_ptr<const EdgeModelView> models,
                         std::shared_ptr<const ltl::Automaton> automaton, const SpecPlannerOptions& options)
    : map_(&map),
      models_(std::move(models)),
      automaton_(std::move(automaton)),
      dead_ends_(std::make_shared<const DeadEnds>(DeadEnds::find(map))),
      options_(options) {}

Result<SpecPlan> SpecPlanner::plan(NodeIndex from, AutomatonState state, Time depart_at) const {
  if (from >= map_->node_count())
    return Error::invalid(fmt::format("node index {} is not below the node count {}", from, map_->node_count()));
  if (state >= automaton_->state_count())
    return Error::invalid(fmt::format("automaton state {} is not below the state count {}", state,
                                      automaton_->state_count()));
  const Mdp mdp = Mdp::build(*map_, *models_, depart_at, dead_ends_);
  RONDO_ASSIGN_OR_RETURN(ProductMdp product, ProductMdp::build(mdp, automaton_));
  ProductSolution solution = options_.use_value_iteration ? ProductValueIteration(options_.value_iteration).solve(product)
                                                          : ProductExactSolver{}.solve(product);
  std::optional<Unsatisfiable> why;
  if (solution.policy.expected_seconds(from, state) == kInfinity) why = why_unsatisfiable(product, from, state);
  return SpecPlan{.from = from, .state = state, .solution = std::move(solution), .unsatisfiable = std::move(why)};
}

}  // namespace rondo::plan
