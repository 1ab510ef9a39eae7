#include "spec_tasks.h"

#include <algorithm>
#include <cmath>

#include "rondo/ltl/task_formula.h"

namespace rondo::exec {
namespace {

// The models with some edges left out: an attempt of a held edge never succeeds.
class WithoutEdges final : public plan::EdgeModelView {
 public:
  WithoutEdges(const plan::EdgeModelView& base, const std::vector<map::EdgeIndex>& held)
      : base_(base), held_(held.begin(), held.end()) {}
  plan::EdgeCrossing outcome(map::EdgeIndex edge, Time at) const override {
    plan::EdgeCrossing o = base_.outcome(edge, at);
    if (std::binary_search(held_.begin(), held_.end(), edge)) o.success_probability = 0.0;
    return o;
  }
  std::uint64_t version() const override { return base_.version(); }
  void attempt_laws(map::EdgeIndex edge, Time at, plan::RouteLeg& leg) const override {
    base_.attempt_laws(edge, at, leg);
  }

 private:
  const plan::EdgeModelView& base_;
  std::vector<map::EdgeIndex> held_;
};

}  // namespace

SpecTasks::SpecTasks(const map::TopoMap& map, std::shared_ptr<const plan::EdgeModelView> models, Duration slot_width)
    : map_(&map), models_(std::move(models)), slot_width_(slot_width) {}

Time SpecTasks::slot_start(Time t) const {
  const auto width = slot_width_.count();
  const auto ms = t.time_since_epoch().count();
  return Time{Duration{ms - ((ms % width) + width) % width}};
}

Result<const plan::SpecPlanner*> SpecTasks::planner(const std::string& formula) const {
  if (const auto it = planners_.find(formula); it != planners_.end()) return it->second.get();
  const map::TopoMap& map = *map_;
  RONDO_ASSIGN_OR_RETURN(auto automaton,
                         ltl::task_automaton(
                             formula, [&map](std::string_view n) { return map.find_node(n).has_value(); }, map.name()));
  RONDO_ASSIGN_OR_RETURN(plan::SpecPlanner p, plan::SpecPlanner::create(map, models_, std::move(automaton)));
  auto shared = std::make_shared<const plan::SpecPlanner>(std::move(p));
  return planners_.emplace(formula, std::move(shared)).first->second.get();
}

SpecTasks::AutomatonState SpecTasks::state_at(const TaskRecord& r, map::NodeIndex here) const {
  const plan::SpecPlanner* p = *planner(r.task.spec);
  // A stored state from another automaton (a changed build) is not trusted: the journey begins again.
  if (r.spec_state && *r.spec_state < p->automaton().state_count()) return p->after_reaching(*r.spec_state, here);
  return p->start_state(here);
}

Result<std::shared_ptr<const plan::SpecPlan>> SpecTasks::slot_plan(const std::string& formula, Time t) const {
  const Time slot = slot_start(t);
  const std::uint64_t version = models_->version();
  const auto key = std::make_pair(formula, slot);
  if (const auto it = plans_.find(key); it != plans_.end() && it->second.version == version) return it->second.plan;
  RONDO_ASSIGN_OR_RETURN(const plan::SpecPlanner* p, planner(formula));
  RONDO_ASSIGN_OR_RETURN(plan::SpecPlan fresh, p->plan(0, p->automaton().initial(), slot));
  if (plans_.size() >= kMaxCachedPlans) {  // the oldest slot starts go first
    auto oldest = std::min_element(plans_.begin(), plans_.end(),
                                   [](const auto& a, const auto& b) { return a.first.second < b.first.second; });
    plans_.erase(oldest);
  }
  auto shared = std::make_shared<const plan::SpecPlan>(std::move(fresh));
  plans_[key] = Entry{.plan = shared, .version = version};
  return shared;
}

Duration SpecTasks::travel(const TaskRecord& r, map::NodeIndex from, Time depart) const {
  auto plan = slot_plan(r.task.spec, depart);
  if (!plan) return kUnreachable;
  const double s = (*plan)->policy().expected_seconds(from, state_at(r, from));
  if (!std::isfinite(s) || s >= to_seconds(kUnreachable)) return kUnreachable;
  return from_seconds(s);
}

std::optional<map::NodeIndex> SpecTasks::end_node(const TaskRecord& r, map::NodeIndex from, Time depart) const {
  auto plan = slot_plan(r.task.spec, depart);
  if (!plan) return std::nullopt;
  return (*plan)->policy().end_node(from, state_at(r, from));
}

std::optional<std::string> SpecTasks::why_unsatisfiable(const TaskRecord& r, map::NodeIndex here, Time t) const {
  if (!planner(r.task.spec)) return planner(r.task.spec).error().message;
  Result<plan::SpecPlan> plan = plan_now(r.task.spec, here, state_at(r, here), t, {});
  if (!plan) return plan.error().message;
  // Edges closed at this time are the scheduler's to weigh (the task may wait for them); a formula
  // that nothing on the map can satisfy from here is not.
  if (plan->unsatisfiable && plan->unsatisfiable->cause != plan::Unsatisfiable::Cause::kUnreachable)
    return plan->unsatisfiable->reason;
  return std::nullopt;
}

Result<plan::SpecPlan> SpecTasks::plan_now(const std::string& formula, map::NodeIndex here, AutomatonState q, Time now,
                                           const std::vector<map::EdgeIndex>& held) const {
  RONDO_ASSIGN_OR_RETURN(const plan::SpecPlanner* p, planner(formula));
  if (held.empty()) {
    RONDO_ASSIGN_OR_RETURN(auto slot, slot_plan(formula, now));
    if (slot->policy().expected_seconds(here, q) < plan::kInfinity) {
      return plan::SpecPlan{.from = here, .state = q, .solution = slot->solution, .unsatisfiable = std::nullopt};
    }
    return p->plan(here, q, slot_start(now));  // says why, naming the blocking nodes
  }
  std::vector<map::EdgeIndex> sorted = held;
  std::sort(sorted.begin(), sorted.end());
  auto without = std::make_shared<const WithoutEdges>(*models_, sorted);
  auto automaton = std::shared_ptr<const ltl::Automaton>(planners_.at(formula), &p->automaton());
  RONDO_ASSIGN_OR_RETURN(plan::SpecPlanner fresh, plan::SpecPlanner::create(*map_, without, automaton));
  return fresh.plan(here, q, now);
}

std::optional<map::NodeIndex> spec_place(const map::TopoMap& map, const TaskRecord& r) {
  if (r.spec_place.empty()) return std::nullopt;
  return map.find_node(r.spec_place);
}

Duration task_travel(const TravelCache& travel, const SpecTasks* specs, const map::TopoMap& map, const TaskRecord& r,
                     map::NodeIndex from, Time depart) {
  if (const auto place = spec_place(map, r)) return travel.travel(from, *place, depart);
  if (r.task.has_spec()) return specs ? specs->travel(r, from, depart) : kUnreachable;
  if (r.task.start_node.empty()) return Duration{0};
  return travel.travel(from, *map.find_node(r.task.start_node), depart);
}

map::NodeIndex task_place(const SpecTasks* specs, const map::TopoMap& map, const TaskRecord& r, map::NodeIndex from,
                          Time depart) {
  if (const auto place = spec_place(map, r)) return *place;
  if (r.task.has_spec()) {
    if (!specs) return from;
    return specs->end_node(r, from, depart).value_or(from);
  }
  return r.task.start_node.empty() ? from : *map.find_node(r.task.start_node);
}

}  // namespace rondo::exec
