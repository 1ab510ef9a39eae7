// A fleet solution under search: routes, which route holds each task, the requests left out, and
// the cost. Private to src/schedule.
#pragma once

#include <vector>

#include "fleet_route.h"

namespace rondo::schedule::detail {

struct FleetSolution {
  std::vector<Tour> routes{};
  std::vector<int> route_of{};    // task -> route index, -1 when unplanned
  std::vector<int> unassigned{};  // requests
  double cost = 0;
  // Robots that may start a route at no price (kVehiclesThenDistance): as many as the ruin
  // emptied, so that work can move to another robot without the count growing.
  int open_budget = 0;
  // When not empty: the only routes insertions may use (a repair's focus).
  std::vector<char> focus{};

  int vehicles() const {
    int v = 0;
    for (const Tour& r : routes) v += r.empty() ? 0 : 1;
    return v;
  }
};

// Cost bookkeeping shared by the construction and the search.
class SolutionOps {
 public:
  SolutionOps(const FleetModel& model, const RouteOps& ops) : m_(model), ops_(ops) {}
  FleetSolution empty_solution() const;
  // Routes in `orders` (task indices per robot), the rest unassigned.
  FleetSolution from_orders(const std::vector<std::vector<int>>& orders) const;
  double drop_cost(int request) const;
  // Σ route costs + drop costs of the unassigned requests and of tasks planned without a task
  // they come `after`.
  double cost(const FleetSolution& s) const;
  void insert(FleetSolution& s, const Insertion& ins, int request) const;
  void remove(FleetSolution& s, int request) const;  // into unassigned
  // Its best insertion over all routes; empty routes only when allow_empty.
  Insertion best_insertion(const FleetSolution& s, int request, bool allow_empty, double blink = 0,
                           std::mt19937_64* rng = nullptr) const;

 private:
  const FleetModel& m_;
  const RouteOps& ops_;
};

}  // namespace rondo::schedule::detail
