#include "scheduling.h"

#include <map>
#include <memory>

#include "rondo/map/map_geometry.h"
#include "rondo/schedule/stop_condition.h"
#include "spec_tasks.h"

namespace rondo::exec {

Outcome drop_outcome(schedule::DropCause cause) {
  switch (cause) {
    case schedule::DropCause::kUnreachable: return Outcome::kOutOfReach;
    case schedule::DropCause::kHigherPriority: return Outcome::kDroppedForHigherPriority;
    case schedule::DropCause::kLowestPriority: return Outcome::kDroppedLowestPriority;
    case schedule::DropCause::kDoesNotFit: break;
  }
  return Outcome::kDoesNotFit;
}

namespace {

// A travel oracle with the spec tasks' locations priced by their SpecPrice.
class WithSpecs final : public schedule::TravelOracle {
 public:
  WithSpecs(std::shared_ptr<const schedule::TravelOracle> base, std::vector<map::NodeIndex> nodes,
            const std::vector<SpecPrice>& specs)
      : base_(std::move(base)), nodes_(std::move(nodes)), specs_(nodes_.size(), nullptr) {
    prices_ = specs;
    for (const SpecPrice& s : prices_) specs_[s.location] = &s;
  }
  std::size_t location_count() const override { return base_->location_count(); }
  Duration travel(schedule::LocationIndex from, schedule::LocationIndex to, Time depart) const override {
    if (const SpecPrice* s = specs_[to]; s && from != to) return s->travel(nodes_[from], depart);
    return base_->travel(from, to, depart);
  }
  Duration lower_bound(schedule::LocationIndex from, schedule::LocationIndex to) const override {
    if (const SpecPrice* s = specs_[to]; s && from != to) return s->lower_bound(nodes_[from]);
    return base_->lower_bound(from, to);
  }
  bool time_dependent() const override { return true; }

 private:
  std::shared_ptr<const schedule::TravelOracle> base_;
  std::vector<map::NodeIndex> nodes_;
  std::vector<SpecPrice> prices_;
  std::vector<const SpecPrice*> specs_;
};

// A travel oracle that arrives no earlier than the robot may stop among the other robots' stops
// (StopsAhead). Moving an arrival to the earliest free start never moves a later one earlier, so
// FIFO holds as in the oracle below; the lower bound is the oracle's.
class AroundStops final : public schedule::TravelOracle {
 public:
  AroundStops(std::shared_ptr<const schedule::TravelOracle> base, const StopsAhead& stops)
      : base_(std::move(base)), stops_(stops) {}
  std::size_t location_count() const override { return base_->location_count(); }
  Duration travel(schedule::LocationIndex from, schedule::LocationIndex to, Time depart) const override {
    const Duration base = base_->travel(from, to, depart);
    if (from == to || base >= kUnreachable || stops_.at[to].empty()) return base;
    return traffic::earliest_free(stops_.at[to], stops_.capacity[to], depart + base, stops_.stay[to]) - depart;
  }
  Duration lower_bound(schedule::LocationIndex from, schedule::LocationIndex to) const override {
    return base_->lower_bound(from, to);
  }
  bool time_dependent() const override { return true; }

 private:
  std::shared_ptr<const schedule::TravelOracle> base_;
  StopsAhead stops_;
};

// The stops at each location of `problem` that the robot gives way to, from when it is next free.
StopsAhead stops_ahead(const PlanAround& around, const schedule::Problem& problem,
                       const std::vector<map::NodeIndex>& nodes, Time free) {
  StopsAhead s{.at = std::vector<std::vector<traffic::Stop>>(nodes.size()),
               .capacity = std::vector<int>(nodes.size(), 1),
               .stay = std::vector<Duration>(nodes.size(), Duration{0})};
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    s.capacity[i] = around.bookings->capacity(nodes[i]);
    for (const traffic::Stop& stop : around.bookings->gives_way_at(around.robot, nodes[i]))
      if (stop.to > free) s.at[i].push_back(stop);
  }
  for (const schedule::ProblemTask& t : problem.tasks)
    s.stay[t.start_location] = std::max(s.stay[t.start_location], t.duration);
  return s;
}

}  // namespace

Duration SpecPrice::travel(map::NodeIndex from, Time depart) const {
  if (seconds.empty()) return kUnreachable;
  const auto slot_at = [&](std::size_t k) {
    const double s = seconds[k][from];
    return s < to_seconds(kUnreachable) ? s : to_seconds(kUnreachable);
  };
  const double width = to_seconds(slot_width);
  const double t = to_seconds(depart - first_slot) / width;
  if (t <= 0) return from_seconds(slot_at(0));
  const std::size_t k = static_cast<std::size_t>(t);
  if (k + 1 >= seconds.size()) return from_seconds(slot_at(seconds.size() - 1));
  const double a = slot_at(k);
  const double b = slot_at(k + 1);
  return from_seconds(a + (b - a) * (t - static_cast<double>(k)));
}

void SpecPrice::repair_fifo() {
  const double width = to_seconds(slot_width);
  for (std::size_t k = 1; k < seconds.size(); ++k)
    for (std::size_t n = 0; n < seconds[k].size(); ++n)
      seconds[k][n] = std::max(seconds[k][n], seconds[k - 1][n] - width);
}

Duration SpecPrice::lower_bound(map::NodeIndex from) const {
  double least = to_seconds(kUnreachable);
  for (const std::vector<double>& slot : seconds) least = std::min(least, slot[from]);
  return from_seconds(std::max(0.0, least));
}

void set_travel(schedule::Problem& problem, const TravelCache& cache, const std::vector<map::NodeIndex>& nodes,
                std::optional<double> risk_alpha, const std::vector<SpecPrice>& specs, double speed,
                const std::optional<StopsAhead>& stops) {
  problem.travel = std::make_shared<SchedulerTravel>(cache, nodes, speed);
  problem.window_travel.reset();
  if (risk_alpha)
    problem.window_travel = std::make_shared<SchedulerQuantileTravel>(cache, nodes, 1.0 - *risk_alpha, speed);
  if (stops) {
    problem.travel = std::make_shared<AroundStops>(problem.travel, *stops);
    if (problem.window_travel) problem.window_travel = std::make_shared<AroundStops>(problem.window_travel, *stops);
  }
  if (specs.empty()) return;
  problem.travel = std::make_shared<WithSpecs>(problem.travel, nodes, specs);
  if (problem.window_travel) problem.window_travel = std::make_shared<WithSpecs>(problem.window_travel, nodes, specs);
}

Result<schedule::TryScheduleResult> schedule_pending(const ScheduleInputs& in, const PendingTasks& pending,
                                             map::NodeIndex here, Time free,
                                             std::optional<schedule::RunningTask> running) {
  RONDO_ASSIGN_OR_RETURN(PendingProblem p, pending_problem(in, pending, here, free, std::move(running)));
  return solve_pending(p.request, in.scheduler, in.polls, nullptr, in.rng);
}

Result<PendingProblem> pending_problem(const ScheduleInputs& in, const PendingTasks& pending, map::NodeIndex here,
                                       Time free, std::optional<schedule::RunningTask> running) {
  schedule::Problem problem;
  std::vector<map::NodeIndex> nodes{here};
  std::map<map::NodeIndex, schedule::LocationIndex> location{{here, 0}};
  const auto location_of = [&](const std::string& name) {
    const map::NodeIndex n = *in.map.find_node(name);
    auto [it, inserted] = location.emplace(n, nodes.size());
    if (inserted) nodes.push_back(n);
    return it->second;
  };
  std::vector<SpecPrice> specs;
  // A spec task is a location of its own, whose node is where its journey is expected to end from
  // where the robot is when next free, departing at its release (docs/ltl.md, "Scheduling").
  const auto spec_location = [&](const TaskRecord& r) {
    const Time release = r.release();
    const map::NodeIndex end = task_place(in.specs, in.map, r, here, std::max(free, release));
    const schedule::LocationIndex at = nodes.size();
    nodes.push_back(end);
    SpecPrice price{.location = at,
                    .first_slot = in.travel.slot_start(std::max(free, release - kSpecLead)),
                    .slot_width = in.specs->slot_width(),
                    .seconds = {}};
    for (Time t = price.first_slot; t <= r.task.window->deadline; t += price.slot_width) {
      std::vector<double>& row = price.seconds.emplace_back(in.map.node_count());
      for (map::NodeIndex n = 0; n < in.map.node_count(); ++n)
        row[n] = to_seconds(task_travel(in.travel, in.specs, in.map, r, n, t));
    }
    price.repair_fifo();
    specs.push_back(std::move(price));
    return at;
  };
  std::map<TaskId, std::size_t> index;
  for (std::size_t i = 0; i < pending.ids.size(); ++i) index.emplace(pending.ids[i], i);
  for (const TaskId& id : pending.ids) {
    const TaskRecord& r = in.book.at(id);
    const Task& t = r.task;
    const schedule::LocationIndex start = t.has_spec() ? spec_location(r) : location_of(t.start_node);
    problem.tasks.push_back({.id = id,
                             .release = r.release(),
                             .deadline = t.window->deadline,
                             .duration = r.remaining(),
                             .priority = t.priority,
                             .start_location = start,
                             .end_location = t.end_node.empty() ? start : location_of(t.end_node)});
    schedule::ProblemTask& pt = problem.tasks.back();
    if (t.delivery)
      pt.transfer = schedule::ItemTransfer{
          .job = t.delivery->job,
          .action = t.delivery->role == DeliveryRole::kPickup ? schedule::ItemAction::kPickup
                                                              : schedule::ItemAction::kDrop,
          .appearance = t.delivery->appearance,
          .load = t.delivery->load};
    for (const TaskId& a : t.after)
      if (const auto it = index.find(a); it != index.end()) pt.after.push_back(it->second);
  }
  std::optional<ChargePlan> battery;
  if (in.battery) {
    const BatteryInputs& b = *in.battery;
    battery = ChargePlan{.estimator = b.estimator, .level = b.level, .reserve = b.reserve, .margin = b.margin,
                         .drift_per_hour = b.drift_per_hour, .drift_variance_per_hour = b.drift_variance_per_hour,
                         .dock = location_of(in.map.node(b.dock).name),
                         .dock_when_waiting_over = b.dock_when_waiting_over};
    battery->metres.reserve(nodes.size() * nodes.size());
    for (map::NodeIndex from : nodes) {
      const std::vector<double> d = map::shortest_metres(in.map, from);
      for (map::NodeIndex to : nodes) battery->metres.push_back(d[to]);
    }
  }
  problem.robot.capacity = in.capacity;
  for (const OnBoard& o : in.on_board)
    problem.robot.on_board.push_back({.job = o.job, .appearance = o.appearance, .load = o.load});
  for (map::NodeIndex n : nodes) problem.location_names.push_back(in.map.node(n).name);
  problem.robot.location = 0;
  problem.robot.time = free;
  std::optional<StopsAhead> stops;
  if (in.around.bookings) stops = stops_ahead(in.around, problem, nodes, free);
  set_travel(problem, in.travel, nodes, in.risk_alpha, specs, in.speed, stops);

  RONDO_RETURN_IF_ERROR(schedule::validate(problem));
  PendingProblem out{.request = {.problem = std::move(problem), .new_tasks = {}, .zone = in.zone},
                     .nodes = std::move(nodes),
                     .risk_alpha = in.risk_alpha,
                     .battery = std::move(battery),
                     .specs = std::move(specs),
                     .speed = in.speed,
                     .stops = std::move(stops)};
  schedule::TryScheduleRequest& request = out.request;
  for (std::size_t i = pending.old_count; i < pending.ids.size(); ++i) request.new_tasks.push_back(i);
  for (std::size_t i = pending.first_reoffered; i < pending.ids.size(); ++i) request.cannot_preempt.push_back(i);
  request.running = std::move(running);
  return out;
}

schedule::TryScheduleResult solve_pending(schedule::TryScheduleRequest& request, schedule::Scheduler& scheduler,
                                          std::int64_t polls, const schedule::StopCondition* also,
                                          std::mt19937_64& rng) {
  schedule::PollBudgetStop budget(polls);
  std::vector<const schedule::StopCondition*> parts{&budget};
  if (also) parts.push_back(also);
  schedule::TryScheduleResult result = schedule::try_schedule(request, scheduler, schedule::AnyStop(parts), rng);
  if (result.outcome != schedule::TryScheduleOutcome::kOldTasksInfeasible) return result;
  // What was planned no longer fits (a task overran, an on-demand task came first): every task
  // competes again, and the lowest priorities give way.
  const int attempts = result.attempts;
  request.new_tasks.clear();
  for (std::size_t i = 0; i < request.problem.tasks.size(); ++i) request.new_tasks.push_back(i);
  schedule::PollBudgetStop again(polls);
  parts[0] = &again;
  result = schedule::try_schedule(request, scheduler, schedule::AnyStop(parts), rng);
  result.attempts += attempts;
  return result;
}

PlannedAnswer solve_planned(PendingProblem& problem, schedule::Scheduler& scheduler, std::int64_t polls,
                            const schedule::StopCondition* also, std::mt19937_64& rng) {
  return plan_charges(problem.request, problem.battery ? &*problem.battery : nullptr,
                      [&](schedule::TryScheduleRequest& r) { return solve_pending(r, scheduler, polls, also, rng); });
}

}  // namespace rondo::exec
