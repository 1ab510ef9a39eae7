// Spec tasks (a task written as a co-safe formula over the map, docs/ltl.md) in the executor: the
// automaton and planner of each formula, built once and kept by its text; the product plan of each
// slot start, kept while the models stand; the expected time of a spec task's journey from a node
// and where it ends, for the scheduler and the dispatcher; and the plan a journey follows now, with
// the edges journeys found blocked left out. One thread uses it: the clock's.
//
//   SpecTasks specs(map, models, slot_width);
//   Duration d = specs.travel(record, from, depart);          // kUnreachable: cannot be satisfied
//   std::optional<map::NodeIndex> end = specs.end_node(record, from, depart);
//   Result<plan::SpecPlan> now = specs.plan_now(record.task.spec, here, q, now, held);
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/exec/map_travel.h"
#include "rondo/exec/task_book.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/edge_model_view.h"
#include "rondo/plan/spec_planner.h"

namespace rondo::exec {

class SpecTasks {
 public:
  using AutomatonState = plan::SpecPlanner::AutomatonState;
  // Slot plans kept; the oldest slot starts go first past it.
  static constexpr std::size_t kMaxCachedPlans = 512;

  // Precondition: `map` outlives this.
  SpecTasks(const map::TopoMap& map, std::shared_ptr<const plan::EdgeModelView> models, Duration slot_width);

  Duration slot_width() const { return slot_width_; }
  // The planner of `formula` (its automaton built once). Errors: the formula's (parse, limits,
  // unknown nodes).
  Result<const plan::SpecPlanner*> planner(const std::string& formula) const;
  // The automaton state of a spec task with the robot at `here`: what its journey reached before
  // (TaskRecord::spec_state) with `here` read, or, for a journey not begun, the start state at
  // `here`. Precondition: r.task.has_spec() and its formula reads.
  AutomatonState state_at(const TaskRecord& r, map::NodeIndex here) const;
  // The plan at the start of the slot that contains `t` (every node and automaton state).
  Result<std::shared_ptr<const plan::SpecPlan>> slot_plan(const std::string& formula, Time t) const;
  // Expected time of the journey of `r` from `from` departing at the start of `depart`'s slot,
  // until its formula is satisfied; kUnreachable when it cannot be.
  Duration travel(const TaskRecord& r, map::NodeIndex from, Time depart) const;
  // Where that journey ends: the node at which the formula is expected to be satisfied.
  std::optional<map::NodeIndex> end_node(const TaskRecord& r, map::NodeIndex from, Time depart) const;
  // Why the formula of `r` cannot be satisfied from `here` whatever the edges' state (naming the
  // nodes that block it), or nothing when it can, or when only edges closed at `t` stop it.
  std::optional<std::string> why_unsatisfiable(const TaskRecord& r, map::NodeIndex here, Time t) const;
  // The plan from (here, q) at `now` on the models with `held` edges left out (a journey's plan:
  // the edges found blocked are not tried until they are likely passable). Without held edges, the
  // slot's plan. Its `unsatisfiable` says why, naming the blocking nodes.
  Result<plan::SpecPlan> plan_now(const std::string& formula, map::NodeIndex here, AutomatonState q, Time now,
                                  const std::vector<map::EdgeIndex>& held) const;

 private:
  struct Entry {
    std::shared_ptr<const plan::SpecPlan> plan;
    std::uint64_t version = 0;
  };
  Time slot_start(Time t) const;

  const map::TopoMap* map_;
  std::shared_ptr<const plan::EdgeModelView> models_;
  Duration slot_width_;
  mutable std::map<std::string, std::shared_ptr<const plan::SpecPlanner>> planners_;
  mutable std::map<std::pair<std::string, Time>, Entry> plans_;
};

// Where a spec task's formula was satisfied (its actions run there), once it was.
std::optional<map::NodeIndex> spec_place(const map::TopoMap& map, const TaskRecord& r);

// A task's journey as the scheduler and the dispatcher price it: to its start node (none: it runs
// where the robot is), or, for a spec task, until its formula is satisfied. `specs` may be null
// when no task has a spec.
Duration task_travel(const TravelCache& travel, const SpecTasks* specs, const map::TopoMap& map, const TaskRecord& r,
                     map::NodeIndex from, Time depart);
// Where such a journey ends and the task's actions run (a spec task: where its formula is expected
// to be satisfied; `from` when it cannot be).
map::NodeIndex task_place(const SpecTasks* specs, const map::TopoMap& map, const TaskRecord& r, map::NodeIndex from,
                          Time depart);

}  // namespace rondo::exec
