// Planning on the product of M_t with a task formula's automaton: hand-made maps for the issue's
// cases (an avoided node forces the long way, "B or C", visiting in the better order, formulas
// that cannot be satisfied and why), through the exact solver, value iteration and SpecPlanner.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "rondo/ltl/parser.h"
#include "rondo/plan/product_blockers.h"
#include "rondo/plan/product_solver.h"
#include "rondo/plan/spec_planner.h"
#include "small_maps.h"

namespace rondo::plan {
namespace {

using testing::outcomes_mdp;
using testing::small_map;

std::shared_ptr<const ltl::Automaton> automaton_of(const std::string& formula) {
  return std::make_shared<const ltl::Automaton>(ltl::Automaton::build(ltl::parse_formula(formula).value()).value());
}

// Both solvers' answers on the same product, for cases that must hold for each.
std::vector<ProductSolution> solve_both(const ProductMdp& product) {
  std::vector<ProductSolution> out;
  out.push_back(ProductExactSolver{}.solve(product));
  out.push_back(ProductValueIteration({.tolerance = 1e-12}).solve(product));
  return out;
}

TEST(Product, AnAvoidedNodeMakesTheRobotTakeTheLongWay) {
  // A>D>S is 20 s, A>B>C>S 30 s; the formula forbids D before S.
  const map::TopoMap m = small_map({"A", "B", "C", "D", "S"}, {"A>D", "D>S", "A>B", "B>C", "C>S"});
  const Mdp mdp = outcomes_mdp(m, {{1, 10}, {1, 10}, {1, 10}, {1, 10}, {1, 10}});
  const ProductMdp product = ProductMdp::build(mdp, automaton_of("!D U S")).value();
  const auto q = product.start_state(0);
  for (const ProductSolution& s : solve_both(product)) {
    EXPECT_EQ(s.policy.next_edge(0, q), 2u);  // A>B
    EXPECT_NEAR(s.policy.expected_seconds(0, q), 30.0, 1e-9);
    EXPECT_EQ(s.policy.end_node(0, q), 4u);
    const std::vector<ProductStep> route = s.policy.route(0, q);
    ASSERT_EQ(route.size(), 3u);
    EXPECT_TRUE(s.policy.satisfied(route.back().next_state));
    EXPECT_EQ(s.policy.satisfaction_probability(0, q), 1.0);
  }
}

TEST(Product, GoesToTheCheaperOfTwoGoalsCountingRetries) {
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "A>C"});
  const auto automaton = automaton_of("F (B | C)");
  {
    const Mdp mdp = outcomes_mdp(m, {{1, 50}, {1, 20}});
    const ProductMdp product = ProductMdp::build(mdp, automaton).value();
    EXPECT_EQ(ProductExactSolver{}.solve(product).policy.next_edge(0, product.start_state(0)), 1u);
  }
  {
    const Mdp mdp = outcomes_mdp(m, {{1, 50}, {0.1, 10}});  // C: 100 s expected with retries
    const ProductMdp product = ProductMdp::build(mdp, automaton).value();
    const ProductSolution s = ProductExactSolver{}.solve(product);
    EXPECT_EQ(s.policy.next_edge(0, product.start_state(0)), 0u);
    EXPECT_NEAR(s.policy.expected_seconds(0, product.start_state(0)), 50.0, 1e-9);
  }
}

TEST(Product, VisitsTwoPlacesInTheBetterOrderAndFollowsTheAutomaton) {
  // A>B>C is 20 s; A>C>B is 5 + 30 s.
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "B>C", "A>C", "C>B"});
  const Mdp mdp = outcomes_mdp(m, {{1, 10}, {1, 10}, {1, 5}, {1, 30}});
  const ProductMdp product = ProductMdp::build(mdp, automaton_of("F B & F C")).value();
  for (const ProductSolution& s : solve_both(product)) {
    const auto q = s.policy.start_state(0);
    EXPECT_EQ(s.policy.next_edge(0, q), 0u);
    EXPECT_NEAR(s.policy.expected_seconds(0, q), 20.0, 1e-9);
    EXPECT_EQ(s.policy.end_node(0, q), 2u);
    const auto at_b = s.policy.after_reaching(q, 1);
    EXPECT_EQ(s.policy.next_edge(1, at_b), 1u);
    EXPECT_NEAR(s.policy.expected_seconds(1, at_b), 10.0, 1e-9);
    EXPECT_TRUE(s.policy.satisfied(s.policy.after_reaching(at_b, 2)));
  }
}

TEST(Product, TheTravelTimeDistributionFollowsTheRoute) {
  // "F B & F C" from A: A>B (p 0.5, 10 s) then B>C (p 1, 10 s): 30 s expected; at least 20 s.
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "B>C"});
  const Mdp mdp = outcomes_mdp(m, {{0.5, 10}, {1, 10}});
  const ProductMdp product = ProductMdp::build(mdp, automaton_of("F B & F C")).value();
  const ProductSolution s = ProductExactSolver{}.solve(product);
  const auto q = s.policy.start_state(0);
  const TravelTimeDistribution d = s.policy.travel_time_distribution(0, q);
  EXPECT_NEAR(d.expected_seconds(), 30.0, 1e-9);
  EXPECT_LE(d.probability_within(19.0).upper, 1e-12);        // two crossings take 20 s at least
  EXPECT_NEAR(d.probability_within(20.5).lower, 0.5, 1e-9);  // B on the first attempt
  EXPECT_NEAR(d.probability_within(30.5).lower, 0.75, 1e-9);
  // From B, "F A & X A" needs A next, and no edge leads back to A.
  const ProductMdp never = ProductMdp::build(mdp, automaton_of("F A & X A")).value();
  const auto stuck = never.start_state(1);
  EXPECT_FALSE(ProductExactSolver{}.solve(never).policy.travel_time_distribution(1, stuck).reachable());
}

TEST(Product, AFormulaSatisfiedAtTheStartNeedsNoMove) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B"});
  const Mdp mdp = outcomes_mdp(m, {{1, 10}});
  const ProductMdp product = ProductMdp::build(mdp, automaton_of("F A")).value();
  const ProductSolution s = ProductExactSolver{}.solve(product);
  const auto q = product.start_state(0);
  EXPECT_TRUE(s.policy.satisfied(q));
  EXPECT_EQ(s.policy.expected_seconds(0, q), 0.0);
  EXPECT_FALSE(s.policy.next_edge(0, q).has_value());
  EXPECT_EQ(s.policy.end_node(0, q), 0u);
}

TEST(Product, AnAvoidedNodeThatCutsEveryWayIsNamed) {
  const map::TopoMap m = small_map({"A", "B", "D", "S"}, {"A>B", "B>D", "D>S"});
  const Mdp mdp = outcomes_mdp(m, {{1, 10}, {1, 10}, {1, 10}});
  const ProductMdp product = ProductMdp::build(mdp, automaton_of("!D U S")).value();
  const auto q = product.start_state(0);
  for (const ProductSolution& s : solve_both(product)) {
    EXPECT_EQ(s.policy.expected_seconds(0, q), kInfinity);
    EXPECT_EQ(s.policy.satisfaction_probability(0, q), 0.0);
    EXPECT_FALSE(s.policy.next_edge(0, q).has_value());
    EXPECT_FALSE(s.policy.end_node(0, q).has_value());
  }
  const std::optional<Unsatisfiable> why = why_unsatisfiable(product, 0, q);
  ASSERT_TRUE(why.has_value());
  EXPECT_EQ(why->cause, Unsatisfiable::Cause::kBlocked);
  EXPECT_EQ(why->blocking_nodes, std::vector<NodeIndex>{2});
  EXPECT_EQ(why->reason, "every way that satisfies the formula from 'A' passes a node it forbids: 'D'");
}

TEST(Product, TwoAvoidedNodesOnTwoWaysAreBothNamed) {
  const map::TopoMap m = small_map({"A", "D", "E", "S"}, {"A>D", "D>S", "A>E", "E>S"});
  const Mdp mdp = outcomes_mdp(m, {{1, 10}, {1, 10}, {1, 10}, {1, 10}});
  const ProductMdp product = ProductMdp::build(mdp, automaton_of("(!D & !E) U S")).value();
  const std::optional<Unsatisfiable> why = why_unsatisfiable(product, 0, product.start_state(0));
  ASSERT_TRUE(why.has_value());
  EXPECT_EQ(why->blocking_nodes, (std::vector<NodeIndex>{1, 2}));
  EXPECT_EQ(why->reason, "every way that satisfies the formula from 'A' passes a node it forbids: 'D', 'E'");
}

TEST(Product, OtherReasonsAFormulaCannotBeSatisfied) {
  const map::TopoMap m = small_map({"A", "B", "D", "Z"}, {"A>B", "B>A", "A>D"});
  const Mdp mdp = outcomes_mdp(m, {{1, 10}, {1, 10}, {0, 10}});  // A>D closed
  using Cause = Unsatisfiable::Cause;
  struct Case {
    std::string formula;
    NodeIndex start;
    Cause cause;
    std::string reason;
  };
  const std::vector<Case> cases = {
      {"F Z", 0, Cause::kUnreachable,
       "no usable route from 'A' satisfies the formula at this time: 'Z' cannot be reached (closed or missing edges)"},
      {"F D", 0, Cause::kUnreachable,
       "no usable route from 'A' satisfies the formula at this time: 'D' cannot be reached (closed or missing edges)"},
      {"!D U B", 2, Cause::kAlreadyBroken, "starting at 'D' breaks the formula"},
      {"F (A & B)", 0, Cause::kNeverSatisfiable, "no route can satisfy the formula: it asks for the impossible"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.formula);
    const ProductMdp product = ProductMdp::build(mdp, automaton_of(c.formula)).value();
    const auto q = product.start_state(c.start);
    EXPECT_EQ(ProductExactSolver{}.solve(product).policy.expected_seconds(c.start, q), kInfinity);
    const std::optional<Unsatisfiable> why = why_unsatisfiable(product, c.start, q);
    ASSERT_TRUE(why.has_value());
    EXPECT_EQ(why->cause, c.cause);
    EXPECT_EQ(why->reason, c.reason);
  }
  // Broken earlier on the way, not by the node the robot is at now.
  const ProductMdp avoid = ProductMdp::build(mdp, automaton_of("!D U B")).value();
  const auto broken = avoid.after_reaching(avoid.start_state(0), 2);
  const std::optional<Unsatisfiable> earlier = why_unsatisfiable(avoid, 0, broken);
  ASSERT_TRUE(earlier.has_value());
  EXPECT_EQ(earlier->cause, Cause::kAlreadyBroken);
  EXPECT_TRUE(earlier->blocking_nodes.empty());
  EXPECT_EQ(earlier->reason, "the nodes reached so far already break the formula");
  const ProductMdp fine = ProductMdp::build(mdp, automaton_of("F B")).value();
  EXPECT_FALSE(why_unsatisfiable(fine, 0, fine.start_state(0)).has_value());
}

TEST(Product, AFormulaNamingANodeTheMapLacksIsRefused) {
  const map::TopoMap m = small_map({"A", "B"}, {"A>B"});
  const Mdp mdp = outcomes_mdp(m, {{1, 10}});
  const Result<ProductMdp> product = ProductMdp::build(mdp, automaton_of("F B & F Nowhere"));
  ASSERT_FALSE(product.ok());
  EXPECT_EQ(product.error().code, ErrorCode::kNotFound);
  EXPECT_EQ(product.error().message, "the formula names node 'Nowhere', which map 'small' does not have");
}

TEST(SpecPlanner, PlansAtTheDepartureTimeAndGoesToTheOtherGoalWhenOneIsClosed) {
  // "B or C": B is nearer, but its edge is closed from t = 1000 s on.
  const map::TopoMap m = small_map({"A", "B", "C"}, {"A>B", "A>C"});
  auto models = std::make_shared<const FunctionEdgeModels>([](map::EdgeIndex e, Time t) {
    if (e == 0) return EdgeCrossing{to_unix_seconds(t) < 1000 ? 1.0 : 0.0, 10.0};
    return EdgeCrossing{1.0, 30.0};
  });
  const SpecPlanner planner = SpecPlanner::create(m, models, automaton_of("F B | F C")).value();
  const auto q = planner.start_state(0);
  const SpecPlan early = planner.plan(0, q, from_unix_seconds(0)).value();
  EXPECT_EQ(early.next_edge(), 0u);
  EXPECT_EQ(early.end_node(), 1u);
  EXPECT_DOUBLE_EQ(early.expected_seconds(), 10.0);
  const SpecPlan late = planner.plan(0, q, from_unix_seconds(2000)).value();
  EXPECT_EQ(late.next_edge(), 1u);
  EXPECT_EQ(late.end_node(), 2u);
  EXPECT_FALSE(late.unsatisfiable.has_value());

  const SpecPlanner avoid = SpecPlanner::create(m, models, automaton_of("!C U B")).value();
  const SpecPlan blocked = avoid.plan(0, avoid.start_state(0), from_unix_seconds(2000)).value();
  ASSERT_TRUE(blocked.unsatisfiable.has_value());
  EXPECT_EQ(blocked.unsatisfiable->cause, Unsatisfiable::Cause::kUnreachable);

  const SpecPlanner vi = SpecPlanner::create(m, models, automaton_of("F B | F C"), {.use_value_iteration = true}).value();
  EXPECT_NEAR(vi.plan(0, q, from_unix_seconds(2000))->expected_seconds(), 30.0, 1e-6);
  EXPECT_EQ(planner.plan(7, q, Time{}).error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(SpecPlanner::create(m, models, automaton_of("F Q")).error().code, ErrorCode::kNotFound);
}

}  // namespace
}  // namespace rondo::plan
