#include "rondo/schedule/fleet_scheduler.h"

#include <algorithm>

#include <fmt/format.h>

#include "fleet_search.h"
#include "rondo/schedule/default_scheduler.h"

namespace rondo::schedule {

namespace {

using detail::FleetModel;
using detail::FleetSearch;
using detail::FleetSolution;

// One robot, the paper's objective, nothing the one-robot Problem cannot say: today's scheduler.
bool one_robot_problem(const FleetProblem& p) {
  if (p.robots.size() != 1 || p.objective != FleetObjective::kSumOfEnds) return false;
  const FleetRobot& robot = p.robots.front();
  if (robot.speed_factor != 1.0) return false;
  for (const FleetTask& f : p.tasks) {
    if (f.due || f.demand != 0) return false;
    if (f.pinned_robot && *f.pinned_robot != 0) return false;
    if (!f.action.empty() && std::find(robot.actions.begin(), robot.actions.end(), f.action) == robot.actions.end())
      return false;
  }
  return true;
}

Problem as_one_robot(const FleetProblem& p) {
  const FleetRobot& robot = p.robots.front();
  Problem one;
  one.robot = {.location = robot.location, .time = robot.free_from, .capacity = robot.capacity};
  for (const FleetTask& f : p.tasks) one.tasks.push_back(f.task);
  one.travel = robot.travel ? robot.travel : p.travel;
  one.return_to = robot.end;
  return one;
}

std::string drop_reason(const FleetModel& m, int task) {
  bool any = false;
  for (int r = 0; r < m.robots() && !any; ++r) any = m.allowed(r, task);
  if (any) return "no robot can fit it beside the other tasks";
  const FleetTask& f = m.problem().tasks[task];
  if (f.pinned_robot) return fmt::format("its robot '{}' cannot run it", m.problem().robots[*f.pinned_robot].name);
  return fmt::format("no robot can run the action '{}'", f.action);
}

// Orders of a solution, less the tasks that come `after` an unplanned task (they are dropped too).
std::vector<std::vector<std::size_t>> orders_of(const FleetModel& m, const FleetSolution& s) {
  std::vector<bool> planned(m.tasks(), false);
  for (const auto& r : s.routes)
    for (int x : r.seq) planned[x] = true;
  for (bool changed = true; changed;) {
    changed = false;
    for (int i = 0; i < m.tasks(); ++i)
      for (int p : m.predecessors(i))
        if (planned[i] && !planned[p]) planned[i] = false, changed = true;
    for (const auto& q : m.requests())  // a pickup and its drop go together
      if (q.drop >= 0 && planned[q.first] != planned[q.drop]) planned[q.first] = planned[q.drop] = false, changed = true;
  }
  std::vector<std::vector<std::size_t>> orders(s.routes.size());
  for (std::size_t r = 0; r < s.routes.size(); ++r)
    for (int x : s.routes[r].seq)
      if (planned[x]) orders[r].push_back(static_cast<std::size_t>(x));
  return orders;
}

FleetPlan to_plan(const FleetModel& m, const FleetSolution& s) {
  std::vector<std::vector<std::size_t>> orders = orders_of(m, s);
  Result<FleetPlan> plan = time_fleet_routes(m.problem(), orders);
  // Without the triangle inequality, leaving a task out can make a route later: then its tasks
  // are dropped from the end until it holds.
  for (std::size_t r = 0; !plan && r < orders.size(); ++r) {
    while (!orders[r].empty()) {
      std::vector<std::vector<std::size_t>> one(orders.size());
      one[r] = orders[r];
      if (time_fleet_routes(m.problem(), one)) break;
      orders[r].pop_back();
    }
    plan = time_fleet_routes(m.problem(), orders);
  }
  FleetPlan out = plan ? *plan : *time_fleet_routes(m.problem(), {});
  for (DroppedTask& d : out.dropped) d.reason = drop_reason(m, static_cast<int>(d.task));
  return out;
}

FleetPlan from_default(const FleetProblem& p, const Schedule& s) {
  std::vector<std::vector<std::size_t>> orders(1, s.order());
  return *time_fleet_routes(p, orders);
}

// The routes of `orders` as the model can hold them: a route that breaks a rule (a window, the
// capacity, the dock) keeps its tasks in order, less each one that cannot be appended where it
// stands (and a delivery half whose other half is left out).
std::vector<std::vector<int>> held_orders(const FleetModel& m, const detail::RouteOps& ops,
                                          const std::vector<std::vector<std::size_t>>& orders) {
  std::vector<std::vector<int>> out(static_cast<std::size_t>(m.robots()));
  for (int r = 0; r < m.robots() && r < static_cast<int>(orders.size()); ++r) {
    detail::Tour tour{.robot = r};
    for (std::size_t x : orders[r]) tour.seq.push_back(static_cast<int>(x));
    ops.update(tour);
    if (!tour.feasible) {
      std::vector<int> kept;
      std::vector<int> left_out;
      for (int x : tour.seq) {
        const detail::Request& q = m.requests()[m.request_of(x)];
        const int partner = x == q.first ? q.drop : q.first;
        if (partner >= 0 && std::find(left_out.begin(), left_out.end(), partner) != left_out.end()) continue;
        detail::Tour next{.robot = r, .seq = kept};
        next.seq.push_back(x);
        ops.update(next);
        if (next.feasible) {
          kept = std::move(next.seq);
        } else {
          left_out.push_back(x);
        }
      }
      // A pickup kept whose drop was left out goes too (the drop came after it).
      std::erase_if(kept, [&](int x) {
        const detail::Request& q = m.requests()[m.request_of(x)];
        return q.drop >= 0 && x == q.first && std::find(kept.begin(), kept.end(), q.drop) == kept.end();
      });
      tour.seq = std::move(kept);
    }
    out[r] = std::move(tour.seq);
  }
  return out;
}

}  // namespace

FleetPlan FleetScheduler::solve(const FleetProblem& problem, const StopCondition& stop) const {
  if (options_.single_robot_default && one_robot_problem(problem)) {
    const Schedule s =
        DefaultScheduler({.seed = options_.seed, .improve = options_.improve}).solve(as_one_robot(problem), stop);
    if (s.status == SolveStatus::kOptimal || s.status == SolveStatus::kFeasible) return from_default(problem, s);
  }
  const FleetModel model(problem);
  FleetSearch search(model, options_, stop);
  FleetSolution s = search.ops().empty_solution();
  search.construct(s);
  if (options_.improve) s = search.improve(std::move(s));
  return to_plan(model, s);
}

FleetPlan FleetScheduler::insert(const FleetProblem& problem, const FleetPlan& plan, std::size_t task,
                                 const StopCondition& stop) const {
  std::vector<std::vector<std::size_t>> orders(problem.robots.size());
  for (std::size_t r = 0; r < plan.routes.size() && r < orders.size(); ++r)
    for (const ScheduledTask& e : plan.routes[r])
      if (e.task != task) orders[r].push_back(e.task);
  return insert(problem, orders, {task}, stop);
}

FleetPlan FleetScheduler::insert(const FleetProblem& problem, const std::vector<std::vector<std::size_t>>& orders,
                                 const std::vector<std::size_t>& tasks, const StopCondition& stop) const {
  const FleetModel model(problem);
  FleetSearch search(model, options_, stop);
  FleetSolution s = search.ops().from_orders(held_orders(model, search.routes(), orders));
  std::vector<int> requests;
  for (std::size_t t : tasks) {
    const int q = model.request_of(static_cast<int>(t));
    if (std::find(requests.begin(), requests.end(), q) == requests.end()) requests.push_back(q);
  }
  search.greedy(s, requests, true, 0.0);
  s.cost = search.ops().cost(s);
  for (int q : requests) s = search.repair_around(std::move(s), q, options_.repair_iterations);
  return to_plan(model, s);
}

}  // namespace rondo::schedule
