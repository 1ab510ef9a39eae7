// Deliberately written without any helper shared with the fleet solver (robot_travel and
// distance_between are the problem's own definitions): a second, plain reading of the rules.
#include "rondo/schedule/fleet_checker.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include <fmt/format.h>

namespace rondo::schedule {

std::string FleetCheckReport::summary() const {
  std::string s;
  for (const auto& v : violations) s += v + "\n";
  return s.empty() ? "ok" : s;
}

namespace {

struct Where {
  long robot = -1;
  long position = -1;
  Time start{};
  Time end{};
};

class FleetChecker {
 public:
  FleetChecker(const FleetProblem& p, const FleetPlan& plan, FleetCheckReport& r)
      : p_(p), plan_(plan), r_(r), where_(p.tasks.size()) {}

  void run() {
    if (plan_.routes.size() != p_.robots.size())
      bad(fmt::format("{} routes for {} robots", plan_.routes.size(), p_.robots.size()));
    if (!count_each_task_once()) return;
    for (std::size_t r = 0; r < std::min(plan_.routes.size(), p_.robots.size()); ++r) check_route(r);
    check_links();
    check_totals();
  }

 private:
  void bad(std::string what) { r_.violations.push_back(std::move(what)); }
  const std::string& id(std::size_t i) const { return p_.tasks[i].task.id; }

  bool count_each_task_once() {
    std::vector<int> seen(p_.tasks.size(), 0);
    for (std::size_t r = 0; r < plan_.routes.size(); ++r)
      for (std::size_t k = 0; k < plan_.routes[r].size(); ++k) {
        const std::size_t i = plan_.routes[r][k].task;
        if (i >= p_.tasks.size()) {
          bad(fmt::format("route {}: task index {} out of range", r, i));
          return false;
        }
        ++seen[i];
        where_[i] = {static_cast<long>(r), static_cast<long>(k), plan_.routes[r][k].start, plan_.routes[r][k].end};
      }
    for (const DroppedTask& d : plan_.dropped) {
      if (d.task >= p_.tasks.size()) {
        bad(fmt::format("dropped task index {} out of range", d.task));
        return false;
      }
      ++seen[d.task];
      r_.dropped.push_back(id(d.task));
      if (d.reason.empty()) bad(fmt::format("dropped task '{}' has no reason", id(d.task)));
    }
    for (std::size_t i = 0; i < p_.tasks.size(); ++i) {
      if (seen[i] > 1) bad(fmt::format("task '{}' appears {} times", id(i), seen[i]));
      if (seen[i] == 0) bad(fmt::format("task '{}' neither planned nor dropped", id(i)));
    }
    return true;
  }

  void check_route(std::size_t r) {
    const FleetRobot& robot = p_.robots[r];
    const auto& route = plan_.routes[r];
    Time previous_end = robot.free_from;
    LocationIndex here = robot.location;
    std::int64_t load = 0;
    std::map<std::string, int> looks;
    std::set<std::string> jobs;
    for (const ScheduledTask& e : route) {
      const FleetTask& f = p_.tasks[e.task];
      const ProblemTask& t = f.task;
      const std::string& name = t.id;
      if (e.depart != previous_end) bad(fmt::format("'{}' on '{}': departs at {}, not when the previous task ends ({})",
                                                    name, robot.name, format_time(e.depart), format_time(previous_end)));
      const Duration need = robot_travel(p_, r, here, t.start_location, e.depart);
      if (e.arrival < e.depart + need) bad(fmt::format("'{}' on '{}': arrives {} after leaving, travel takes {}", name,
                                                       robot.name, format_duration(e.arrival - e.depart), format_duration(need)));
      if (e.start < e.arrival) bad(fmt::format("'{}': starts before arriving", name));
      if (e.start < t.release) bad(fmt::format("'{}': starts before its release", name));
      if (e.end != e.start + t.duration) bad(fmt::format("'{}': end != start + duration", name));
      if (t.deadline_on == DeadlineOn::kEnd ? e.end > t.deadline : e.start > t.deadline)
        bad(fmt::format("'{}': misses its deadline {}", name, format_time(t.deadline)));
      if (!f.action.empty() && std::find(robot.actions.begin(), robot.actions.end(), f.action) == robot.actions.end())
        bad(fmt::format("'{}': needs action '{}', which robot '{}' cannot run", name, f.action, robot.name));
      if (f.pinned_robot && *f.pinned_robot != r)
        bad(fmt::format("'{}': pinned to robot {}, planned on '{}'", name, *f.pinned_robot, robot.name));
      if (f.demand != 0) {
        load += f.demand;
        if (robot.capacity > 0 && load > robot.capacity)
          bad(fmt::format("'{}': load {} exceeds the capacity {} of '{}'", name, load, robot.capacity, robot.name));
      }
      if (t.transfer) check_item(t, robot, load, looks, jobs);
      sum_ends_ += to_seconds(e.end - robot.free_from);
      if (f.due && e.end > *f.due) lateness_ += to_seconds(e.end - *f.due) * (1 + t.priority);
      distance_ += p_.distance_between(here, t.start_location);
      previous_end = e.end;
      here = t.end_location;
    }
    if (!jobs.empty()) bad(fmt::format("robot '{}' ends with {} item(s) on board", robot.name, jobs.size()));
    if (route.empty()) return;
    ++vehicles_;
    if (robot.end) {
      const Time back = previous_end + robot_travel(p_, r, here, robot.end->location, previous_end);
      distance_ += p_.distance_between(here, robot.end->location);
      if (back > robot.end->deadline)
        bad(fmt::format("robot '{}': back at its dock at {}, after {}", robot.name, format_time(back),
                        format_time(robot.end->deadline)));
    }
  }

  void check_item(const ProblemTask& t, const FleetRobot& robot, std::int64_t& load, std::map<std::string, int>& looks,
                  std::set<std::string>& jobs) {
    const ItemTransfer& x = *t.transfer;
    if (x.action == ItemAction::kPickup) {
      load += x.load;
      if (robot.capacity > 0 && load > robot.capacity)
        bad(fmt::format("'{}': load {} exceeds the capacity {} of '{}'", t.id, load, robot.capacity, robot.name));
      if (!x.appearance.empty() && looks[x.appearance]++ > 0)
        bad(fmt::format("'{}': picks up a second item that looks like '{}'", t.id, x.appearance));
      jobs.insert(x.job);
    } else {
      if (!jobs.count(x.job)) bad(fmt::format("'{}': drops job '{}', not on board of '{}'", t.id, x.job, robot.name));
      jobs.erase(x.job);
      load -= x.load;
      if (!x.appearance.empty()) looks[x.appearance]--;
    }
  }

  void check_links() {
    for (std::size_t i = 0; i < p_.tasks.size(); ++i) {
      if (where_[i].robot < 0) continue;
      for (std::size_t a : p_.tasks[i].task.after) {
        if (a >= p_.tasks.size()) continue;
        if (where_[a].robot < 0) bad(fmt::format("'{}': planned without '{}', which must end first", id(i), id(a)));
        else if (where_[a].robot != where_[i].robot)
          bad(fmt::format("'{}' and '{}', linked by `after`, are on different robots", id(i), id(a)));
        else if (where_[a].end > where_[i].start)
          bad(fmt::format("'{}': starts before '{}' ends, which must end first", id(i), id(a)));
      }
    }
    // A pickup planned without its drop (the drop without its pickup is caught on its route).
    for (std::size_t i = 0; i < p_.tasks.size(); ++i) {
      const auto& x = p_.tasks[i].task.transfer;
      if (!x || x->action != ItemAction::kPickup || where_[i].robot < 0) continue;
      for (std::size_t j = 0; j < p_.tasks.size(); ++j) {
        const auto& y = p_.tasks[j].task.transfer;
        if (y && y->action == ItemAction::kDrop && y->job == x->job && where_[j].robot < 0)
          bad(fmt::format("'{}': picked up, but its drop '{}' is not planned", id(i), id(j)));
      }
    }
  }

  void check_totals() {
    double drops = 0;
    for (const DroppedTask& d : plan_.dropped) drops += p_.costs.drop_seconds * (1 + p_.tasks[d.task].task.priority);
    r_.recomputed_distance = distance_;
    r_.recomputed_objective = p_.objective == FleetObjective::kSumOfEnds
                                  ? sum_ends_ + p_.costs.lateness_per_second * lateness_ + drops
                                  : distance_ + drops;
    if (vehicles_ != plan_.vehicles) bad(fmt::format("reported {} vehicles, recomputed {}", plan_.vehicles, vehicles_));
    auto close = [](double a, double b) { return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b)); };
    if (!close(plan_.distance, distance_))
      bad(fmt::format("reported distance {:.6f}, recomputed {:.6f}", plan_.distance, distance_));
    if (!close(plan_.objective, r_.recomputed_objective))
      bad(fmt::format("reported objective {:.6f}, recomputed {:.6f}", plan_.objective, r_.recomputed_objective));
  }

  const FleetProblem& p_;
  const FleetPlan& plan_;
  FleetCheckReport& r_;
  std::vector<Where> where_;
  double sum_ends_ = 0, lateness_ = 0, distance_ = 0;
  std::size_t vehicles_ = 0;
};

}  // namespace

FleetCheckReport check_fleet_plan(const FleetProblem& problem, const FleetPlan& plan) {
  FleetCheckReport r;
  FleetChecker(problem, plan, r).run();
  return r;
}

}  // namespace rondo::schedule
