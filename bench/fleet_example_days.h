// Robot days of the fleet example (examples/fleet) as fleet problems, for the allocation benches:
// its map's travel (the distance prior, static), its routines' instances and its requests of one
// local day (the requests drawn with the day's own seed), its robots' starts, actions, capacities
// and speeds, every robot free at its start from local midnight.
//
//   auto example = load_fleet_example("examples/fleet");
//   FleetProblem day = example->day(3, {.copies = 4, .request_factor = 4});   // 20 robots
//
// A task's window is its window, as the robots' own problems have it. The rmf baseline does not
// consider deadlines at all: its answer is checked against with_soft_deadlines(day), where a
// deadline is a `due` (lateness past it is priced, and counted as a deadline missed) and every
// task may end until the next local noon. A plan that meets the hard deadlines passes both.
// A person's call for a robot (on-demand) must end within `on_demand_within` of the call.
#pragma once

#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/routine.h"
#include "rondo/core/task_codec.h"
#include "rondo/schedule/fleet_problem.h"
#include "rondo/sim/request_generator.h"
#include "schedule_map_travel.h"

namespace rondo::bench {

struct ExampleDayOptions {
  int copies = 1;             // robots: the example's, this many times over (same starts)
  double request_factor = 1;  // people's calls: the example's rate times this
  Duration on_demand_within = minutes(30);
  std::uint64_t seed = 1;
};

struct ExampleRobot {
  std::string name, start;
  std::vector<std::string> actions;
  std::int64_t capacity = 0;
  double speed = 1;
};

class FleetExample {
 public:
  static Result<FleetExample> load(const std::filesystem::path& folder) {
    FleetExample ex;
    RONDO_ASSIGN_OR_RETURN(const Document deployment, Document::load(folder / "deployment.yaml"));
    const Field root = deployment.root();
    RONDO_ASSIGN_OR_RETURN(const Field zone, root.required("time_zone"));
    RONDO_ASSIGN_OR_RETURN(const std::string zone_name, zone.as_string());
    RONDO_ASSIGN_OR_RETURN(ex.zone_, TimeZone::named(zone_name));
    RONDO_ASSIGN_OR_RETURN(const Field start, root.required("start"));
    RONDO_ASSIGN_OR_RETURN(const Time first, start.as_time(&ex.zone_));
    ex.first_ = ex.zone_.local_date(first);
    RONDO_ASSIGN_OR_RETURN(const Field dock, root.required("dock"));
    RONDO_ASSIGN_OR_RETURN(const std::string dock_name, dock.as_string());
    RONDO_ASSIGN_OR_RETURN(const Field robots, root.required("robots"));
    RONDO_ASSIGN_OR_RETURN(const std::vector<Field> entries, robots.items());
    for (const Field& e : entries) {
      ExampleRobot r;
      RONDO_ASSIGN_OR_RETURN(const Field name, e.required("name"));
      RONDO_ASSIGN_OR_RETURN(r.name, name.as_string());
      r.start = dock_name;
      for (const char* key : {"dock", "start"})
        if (auto f = e.optional(key)) {
          RONDO_ASSIGN_OR_RETURN(r.start, f->as_string());
        }
      if (auto f = e.optional("actions")) {
        RONDO_ASSIGN_OR_RETURN(const std::vector<Field> actions, f->items());
        for (const Field& a : actions) {
          RONDO_ASSIGN_OR_RETURN(std::string action, a.as_string());
          r.actions.push_back(std::move(action));
        }
      }
      if (auto f = e.optional("capacity")) {
        RONDO_ASSIGN_OR_RETURN(r.capacity, f->as_int());
      }
      if (auto f = e.optional("speed")) {
        RONDO_ASSIGN_OR_RETURN(r.speed, f->as_number());
      }
      ex.robots_.push_back(std::move(r));
    }
    RONDO_ASSIGN_OR_RETURN(ex.map_, map::load_map(folder / "map.yaml"));
    RONDO_ASSIGN_OR_RETURN(ex.matrix_, map_travel((folder / "map.yaml").string(), dock_name, first));
    for (std::size_t i = 0; i < ex.matrix_.names.size(); ++i) ex.location_[ex.matrix_.names[i]] = i;
    RONDO_ASSIGN_OR_RETURN(const TaskFile routines, load_task_file(folder / "routines.yaml"));
    ex.routines_ = routines.routines;
    RONDO_ASSIGN_OR_RETURN(sim::RequestGenerator people,
                           sim::RequestGenerator::load(folder / "requests.yaml", ex.map_, ex.zone_));
    ex.requests_ = people.spec();
    return ex;
  }

  // Day `day` (0: the deployment's first) as one fleet problem under the sum of ends.
  Result<schedule::FleetProblem> day(int day, const ExampleDayOptions& o) const {
    const auto date = std::chrono::year_month_day{std::chrono::sys_days{first_} + std::chrono::days{day}};
    const Time midnight = zone_.at(date, Duration{0});
    schedule::FleetProblem p;
    p.travel = matrix_.travel;
    for (int c = 0; c < o.copies; ++c)
      for (const ExampleRobot& r : robots_) {
        RONDO_ASSIGN_OR_RETURN(const schedule::LocationIndex at, location(r.start));
        p.robots.push_back({.name = o.copies == 1 ? r.name : fmt::format("{}-{}", r.name, c + 1),
                            .location = at,
                            .free_from = midnight,
                            .end = std::nullopt,
                            .actions = r.actions,
                            .capacity = r.capacity,
                            .speed_factor = r.speed,
                            .travel = nullptr});
      }
    std::vector<Task> tasks;
    for (const Routine& r : routines_)
      for (Task& t : instances_on(r, date, zone_)) tasks.push_back(std::move(t));
    sim::RequestSpec spec = requests_;
    spec.per_day *= o.request_factor;
    sim::Rng rng(o.seed * 1000003 + static_cast<std::uint64_t>(day));
    for (const sim::Request& call : sim::RequestGenerator(spec, zone_).between(midnight, midnight + hours(24), rng))
      for (Task t : call.tasks()) {
        if (!t.window) t.window = TimeWindow{call.at, call.at + o.on_demand_within + t.duration};
        tasks.push_back(std::move(t));
      }
    for (const Task& t : tasks) {
      RONDO_ASSIGN_OR_RETURN(const schedule::LocationIndex at, location(t.start_node));
      schedule::FleetTask f;
      f.task = {.id = t.id,
                .release = t.window->release,
                .deadline = t.window->deadline,
                .duration = t.duration,
                .priority = t.priority,
                .start_location = at,
                .end_location = at};
      if (!t.end_node.empty()) {
        RONDO_ASSIGN_OR_RETURN(f.task.end_location, location(t.end_node));
      }
      if (t.delivery)
        f.task.transfer =
            schedule::ItemTransfer{.job = t.delivery->job,
                                   .action = t.delivery->role == DeliveryRole::kPickup ? schedule::ItemAction::kPickup
                                                                                       : schedule::ItemAction::kDrop,
                                   .appearance = t.delivery->appearance,
                                   .load = t.delivery->load};
      if (!t.actions.empty()) f.action = t.actions.front().name;
      p.tasks.push_back(std::move(f));
    }
    return p;
  }

  // The same day with every deadline soft (a `due`), every task allowed to end until the next
  // local noon.
  schedule::FleetProblem with_soft_deadlines(schedule::FleetProblem p) const {
    const auto date = zone_.local_date(p.robots.front().free_from);
    const Time noon =
        zone_.at(std::chrono::year_month_day{std::chrono::sys_days{date} + std::chrono::days{1}}, hours(12));
    for (schedule::FleetTask& f : p.tasks) {
      f.due = f.task.deadline;
      f.task.deadline = std::max(noon, f.task.deadline);
    }
    return p;
  }

  const TimeZone& zone() const { return zone_; }
  std::chrono::year_month_day first_day() const { return first_; }

 private:
  Result<schedule::LocationIndex> location(const std::string& node) const {
    auto it = location_.find(node);
    if (it == location_.end()) return Error::not_found(fmt::format("node '{}' is not reachable from the dock", node));
    return it->second;
  }

  TimeZone zone_ = TimeZone::utc();
  std::chrono::year_month_day first_{};
  std::vector<ExampleRobot> robots_;
  map::TopoMap map_;
  MapMatrix matrix_;
  std::map<std::string, schedule::LocationIndex> location_;
  std::vector<Routine> routines_;
  sim::RequestSpec requests_;
};

}  // namespace rondo::bench
