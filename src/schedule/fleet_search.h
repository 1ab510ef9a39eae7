// The fleet solver's search: regret construction, ruin and recreate, route minimisation and the
// annealing loop. Private to src/schedule; FleetScheduler drives it.
#pragma once

#include <random>
#include <vector>

#include "fleet_solution.h"
#include "rondo/schedule/fleet_scheduler.h"

namespace rondo::schedule::detail {

class FleetSearch {
 public:
  FleetSearch(const FleetModel& model, const FleetSchedulerOptions& options, const StopCondition& stop);

  // Regret-2 insertion of every unassigned request (empty robots allowed).
  void construct(FleetSolution& s);
  // Tour minimisation (hierarchical objective), then annealing until `stop`; returns the best.
  FleetSolution improve(FleetSolution s);
  // A few ruin-and-recreate rounds around one request (insert()'s repair); returns the best.
  FleetSolution repair_around(FleetSolution s, int request, std::size_t iterations);
  const SolutionOps& ops() const { return sol_; }
  const RouteOps& routes() const { return routes_; }

  // Removal heuristics: each takes requests out of `s` into s.unassigned.
  void ruin_random(FleetSolution& s, int count);
  void ruin_related(FleetSolution& s, int count, int seed_request = -1);
  void ruin_strings(FleetSolution& s, int count);
  void ruin_route(FleetSolution& s);
  // Reinsertion: greedy in a random, far-first or tight-window-first order with blinks, or regret-2.
  void recreate(FleetSolution& s, bool allow_empty);
  void greedy(FleetSolution& s, std::vector<int> order, bool allow_empty, double blink);
  void regret(FleetSolution& s, std::vector<int> order, bool allow_empty);

 private:
  bool stopped();
  void report(const FleetSolution& s, std::size_t iteration) const;
  void ruin(FleetSolution& s);
  int removal_count();
  bool minimise_routes(FleetSolution& best, int rank);
  void minimise_all_routes(FleetSolution& best);
  int vehicle_lower_bound() const;
  void anneal(FleetSolution& best);
  void descend(FleetSolution& s);  // relocate and 2-opt* to a local optimum

  const FleetModel& m_;
  FleetSchedulerOptions options_;
  const StopCondition& stop_;
  RouteOps routes_;
  SolutionOps sol_;
  std::mt19937_64 rng_;
  bool stopped_ = false;
};

}  // namespace rondo::schedule::detail
