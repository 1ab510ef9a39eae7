// Plans a task written as a co-safe formula over the map (a "spec task", docs/ltl.md) on the
// learned models, from any (node, automaton state) at any departure time: what the executor asks
// when it starts such a task, after each failed edge, and after a preemption, and what the
// scheduler asks to price it.
//
//   auto automaton = std::make_shared<const ltl::Automaton>(
//       ltl::Automaton::build(ltl::parse_formula("!Kitchen U (EastDoor & (!Kitchen U WestDoor))").value()).value());
//   SpecPlanner planner = SpecPlanner::create(map, models, automaton).value();
//   auto q = planner.start_state(here);
//   SpecPlan plan = planner.plan(here, q, now).value();
//   if (plan.unsatisfiable) refuse(plan.unsatisfiable->reason);        // names the blocking nodes
//   robot.navigate(*plan.next_edge());
//   ... edge done, robot at j: q = planner.after_reaching(q, j); re-plan or follow plan.policy()
//   schedule(plan.expected_seconds(), plan.end_node());
//
// Each plan() builds M_t at the departure time (the edges read once, as for a single target),
// its product with the automaton, and solves it: the exact solver by default (its preconditions
// always hold on such products, docs/ltl.md), or value iteration when asked.
#pragma once

#include <memory>
#include <optional>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/ltl/automaton.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/edge_model_view.h"
#include "rondo/plan/product_blockers.h"
#include "rondo/plan/product_solver.h"

namespace rondo::plan {

struct SpecPlannerOptions {
  bool use_value_iteration = false;  // the reference solver instead of the exact one
  ProductValueIterationOptions value_iteration{};
};

// The answer of one plan() from (from, state).
struct SpecPlan {
  NodeIndex from = 0;
  ltl::Automaton::State state = 0;
  ProductSolution solution;
  // Set when the formula cannot be satisfied from (from, state): why, naming the nodes.
  std::optional<Unsatisfiable> unsatisfiable;

  const ProductPolicy& policy() const { return solution.policy; }
  std::optional<EdgeIndex> next_edge() const { return policy().next_edge(from, state); }
  double expected_seconds() const { return policy().expected_seconds(from, state); }
  std::optional<NodeIndex> end_node() const { return policy().end_node(from, state); }
};

class SpecPlanner {
 public:
  using AutomatonState = ltl::Automaton::State;

  // An error (kNotFound) when the formula names a node `map` does not have. `map` must outlive
  // the planner; `models` and `automaton` are shared.
  static Result<SpecPlanner> create(const map::TopoMap& map, std::shared_ptr<const EdgeModelView> models,
                                    std::shared_ptr<const ltl::Automaton> automaton,
                                    const SpecPlannerOptions& options = {});

  const ltl::Automaton& automaton() const { return *automaton_; }
  AutomatonState start_state(NodeIndex node) const { return automaton_->next(automaton_->initial(), name(node)); }
  AutomatonState after_reaching(AutomatonState q, NodeIndex node) const { return automaton_->next(q, name(node)); }

  // An error (kInvalidInput) only for a node or automaton state out of range.
  Result<SpecPlan> plan(NodeIndex from, AutomatonState state, Time depart_at) const;

 private:
  SpecPlanner(const map::TopoMap& map, std::shared_ptr<const EdgeModelView> models,
              std::shared_ptr<const ltl::Automaton> automaton, const SpecPlannerOptions& options);
  const std::string& name(NodeIndex node) const { return map_->node(node).name; }

  const map::TopoMap* map_;
  std::shared_ptr<const EdgeModelView> models_;
  std::shared_ptr<const ltl::Automaton> automaton_;
  std::shared_ptr<const DeadEnds> dead_ends_;
  SpecPlannerOptions options_;
};

}  // namespace rondo::plan
