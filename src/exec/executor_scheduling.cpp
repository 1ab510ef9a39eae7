// The executor rescheduling: which tasks are pending, where and when the robot is next free, the
// scheduler's answer applied to the queues, and the tasks dropped for now.
#include <fmt/format.h>

#include <algorithm>

#include "charging.h"
#include "dispatcher.h"
#include "rondo/exec/executor.h"
#include "scheduling.h"
#include "spec_tasks.h"
#include "task_run.h"
#include "text.h"

namespace rondo::exec {

std::pair<map::NodeIndex, Time> Executor::free_at() const {
  const Time now = clock_.now();
  map::NodeIndex here = robot_.location();
  Time t = now;
  // Runs a task after what is already planned: from `here` at `t`, or, when it is acting, until
  // its actions are expected to end (`acting_until`).
  const auto run = [&](const TaskRecord& r, std::optional<Time> acting_until) {
    const Task& task = r.task;
    const map::NodeIndex start = task_place(building_.spec_tasks.get(), map_, r, here, t);
    if (acting_until) {
      t = std::max(now, *acting_until);
    } else {
      Time s = t + task_travel(travel_, building_.spec_tasks.get(), map_, r, here, t);
      if (task.window) s = std::max(s, r.release());
      t = s + r.remaining();
    }
    here = task.end_node.empty() ? start : *map_.find_node(task.end_node);
  };
  if (run_ && !run_->waiting()) run(book_.at(run_->id()), run_->acting_until());
  // Below the hard threshold (to the dock, and charged back to the resume level), or in a planned
  // charge (until its target or its end).
  if (charging_->low() || charging_->planned()) {
    t += travel_.travel(here, options_.dock, t) + charging_->time_to_charge();
    here = options_.dock;
  }
  for (const TaskId& id : dispatcher_->on_demand())  // one held back for a blocked way comes later
    if (!book_.at(id).not_before || *book_.at(id).not_before <= now) run(book_.at(id), std::nullopt);
  return {here, t};
}

namespace {

// Keeps at most `limit` of the new and offered-again tasks, the soonest due first (tasks of a
// delivery or chained by `after` always stay: the problem needs their partners); the new ones left
// out go to `held_over`, the offered-again ones stay dropped for now until the next reschedule.
void hold_over(const TaskBook& book, std::vector<TaskId>& new_ids, std::vector<TaskId>& offered_again,
               std::size_t limit, std::vector<TaskId>& held_over) {
  if (new_ids.size() + offered_again.size() <= limit) return;
  struct Candidate {
    Time latest;
    bool is_new;
    TaskId id;
  };
  std::vector<Candidate> all;
  std::size_t pinned = 0;
  const auto due = [&](const TaskId& id, bool is_new) {
    const TaskRecord& r = book.at(id);
    const bool tied = r.task.delivery.has_value() || !r.task.after.empty() || !r.task.window;
    if (tied) ++pinned;
    all.push_back({tied ? Time::min() : r.latest_start(Duration{0}), is_new, id});
  };
  for (const TaskId& id : new_ids) due(id, true);
  for (const TaskId& id : offered_again) due(id, false);
  std::stable_sort(all.begin(), all.end(), [](const Candidate& a, const Candidate& b) { return a.latest < b.latest; });
  new_ids.clear();
  offered_again.clear();
  const std::size_t keep = std::max(limit, pinned);
  for (std::size_t i = 0; i < all.size(); ++i) {
    if (i < keep)
      (all[i].is_new ? new_ids : offered_again).push_back(std::move(all[i].id));
    else if (all[i].is_new)
      held_over.push_back(std::move(all[i].id));
  }
}

}  // namespace

std::vector<TaskId> Executor::reoffer_deferred() {
  std::vector<TaskId> still;
  const Time now = clock_.now();
  for (const TaskId& id : dispatcher_->deferred()) {
    TaskRecord& r = book_.at(id);
    if (r.state != TaskState::kQueued || !r.dropped_for_now) continue;
    if (now + r.remaining() <= r.task.window->deadline) {
      still.push_back(id);
      continue;
    }
    const auto [outcome, reason] = *r.dropped_for_now;
    book_.transition(id, TaskState::kDropped, outcome, reason);
  }
  dispatcher_->keep_deferred(still);
  return still;
}

void Executor::reschedule(std::vector<TaskId> new_ids, const std::string& why) {
  if (options_.background_scheduling) return reschedule_in_background(std::move(new_ids), why);
  std::optional<ScheduleCall> call = prepare_schedule(new_ids, why);
  if (!call) return;
  const PlannedAnswer answer = solve_planned(call->problem, *scheduler_, options_.scheduler_polls, nullptr, rng_);
  finish_schedule(call->pending.ids, std::move(new_ids), answer, why);
}

std::optional<ScheduleCall> Executor::prepare_schedule(std::vector<TaskId>& new_ids, const std::string& why,
                                                       std::vector<TaskId>* held_over) {
  std::vector<TaskId> offered_again = reoffer_deferred();
  for (TaskId& back : settle_jobs()) new_ids.push_back(std::move(back));
  if (held_over && options_.background_offered > 0)
    hold_over(book_, new_ids, offered_again, options_.background_offered, *held_over);
  PendingTasks pending;
  std::vector<TaskId>& ids = pending.ids;
  const auto add = [this, &ids](const TaskId& id) {  // a task waiting for its door stays out
    if (std::find(ids.begin(), ids.end(), id) == ids.end() && !blocked(id)) ids.push_back(id);
  };
  if (run_ && run_->waiting()) add(run_->id());  // waiting = still pending
  for (const TaskId& id : dispatcher_->planned()) add(id);
  pending.old_count = ids.size();
  for (const TaskId& id : new_ids) {
    // A spec task whose formula cannot be satisfied from here is dropped at once, saying why.
    if (const TaskRecord& r = book_.at(id); r.task.has_spec() && r.task.window && r.spec_place.empty()) {
      if (std::optional<std::string> no = building_.spec_tasks->why_unsatisfiable(
              r, robot_.location(), std::max(clock_.now(), r.task.window->release))) {
        book_.transition(id, TaskState::kDropped, Outcome::kSpecUnsatisfiable, "spec unsatisfiable: " + *no);
        continue;
      }
    }
    add(id);
  }
  pending.first_reoffered = ids.size();
  for (const TaskId& id : offered_again) add(id);
  if (ids.empty()) {
    dispatcher_->follow_schedule({});
    after_schedule(why);
    return std::nullopt;
  }
  refresh_learned_durations(ids);
  const auto [here, free] = free_at();
  std::optional<schedule::RunningTask> running;
  if (run_ && !run_->waiting()) {
    const Task& t = run_->task();
    // An on-demand task is never given up for scheduled work.
    running = schedule::RunningTask{run_->id(), t.priority, t.kind == TaskKind::kStandard && interruptible_now()};
  }
  ScheduleInputs in{.map = map_,
                    .travel = travel_,
                    .book = book_,
                    .zone = zone_,
                    .scheduler = *scheduler_,
                    .polls = options_.scheduler_polls,
                    .rng = rng_,
                    .capacity = options_.capacity,
                    .on_board = on_board_when_free(),
                    .risk_alpha = options_.risk_alpha,
                    .specs = building_.spec_tasks.get(),
                    .speed = building_.speeds.factor(options_.robot_name)};
  if (booking_) in.around = PlanAround{.bookings = building_.bookings, .robot = *booking_};
  if (options_.battery_planning) {
    read_battery();
    charging_->drift().observe(clock_.now(), charging_->level());
    in.battery = BatteryInputs{.estimator = charging_->estimator(),
                               .level = charging_->level_when_free(free, run_ && !run_->waiting()),
                               .reserve = options_.battery_reserve, .margin = options_.battery_margin,
                               .drift_per_hour = charging_->drift().per_hour(),
                               .drift_variance_per_hour = charging_->drift().variance_per_hour(),
                               .dock = options_.dock, .dock_when_waiting_over = options_.dock_when_waiting_over};
  }
  auto problem = pending_problem(in, pending, here, free, running);
  if (!problem) {  // the pending tasks do not make a well-formed problem: keep the plan as it is
    book_.note_schedule(EventKind::kNotRescheduled, Outcome::kNone, fmt::format("{}: {}", why, problem.error().message));
    return std::nullopt;
  }
  return ScheduleCall{.pending = std::move(pending), .problem = std::move(*problem)};
}

void Executor::finish_schedule(const std::vector<TaskId>& ids, std::vector<TaskId> new_ids,
                               const PlannedAnswer& answer, const std::string& why) {
  const schedule::TryScheduleResult& result = answer.result;
  stats_.schedules += result.attempts;
  if (result.outcome == schedule::TryScheduleOutcome::kPreemptRunning) {
    preempt_for(Outcome::kOutranked, "outranked by new tasks: " + result.preempt_reason, std::move(new_ids));
    return;
  }
  apply_schedule(ids, answer, why);
  after_schedule(why);
  offer_again_at_next_slot();
}

// Under the chance constraint a route through an edge that has just failed can be out of reach of
// every window for a while (its quantile holds many failed attempts), and a robot left idle by
// that has nothing else to reschedule it: the tasks dropped for now would wait, unoffered, until
// their windows passed (validation seed 106 of examples/witham: a day with no task done). So they
// are offered again at the next slot start, when the travel estimates may have moved.
void Executor::offer_again_at_next_slot() {
  if (!options_.risk_alpha || dispatcher_->deferred().empty() || offer_again_ != 0) return;
  const Time at = travel_.slot_start(clock_.now()) + options_.slot_width;
  offer_again_ = clock_.schedule_at(at, [this] {
    offer_again_ = 0;
    if (dispatcher_->deferred().empty()) return;
    reschedule({}, "tasks dropped for now offered again at the slot start");
    kick();  // an idle robot starts what fits again
  });
}

void Executor::apply_charges(const std::vector<TaskId>& ids, const PlannedAnswer& answer, const std::string& why) {
  const std::vector<schedule::ScheduledTask>& entries = answer.result.schedule.entries;
  std::vector<PlannedCharge> charges;
  for (std::size_t pos = 0; pos < entries.size(); ++pos) {
    if (entries[pos].task < ids.size()) continue;
    PlannedCharge c{.start = entries[pos].start, .end = entries[pos].end,
                    .target = pos < answer.levels.size() ? std::min(answer.levels[pos], 1.0) : 1.0};
    for (std::size_t next = pos + 1; next < entries.size() && !c.before; ++next)
      if (entries[next].task < ids.size() && !book_.finished(ids[entries[next].task]))
        c.before = ids[entries[next].task];
    charges.push_back(c);
  }
  const std::vector<PlannedCharge>& old = dispatcher_->charges();
  const bool moved = charges.size() != old.size() ||
                     !std::equal(charges.begin(), charges.end(), old.begin(), [](const auto& a, const auto& b) {
                       return a.before == b.before && std::chrono::abs(a.start - b.start) < minutes(15);
                     });
  if (moved)
    for (const PlannedCharge& c : charges)
      book_.note_schedule(EventKind::kChargePlanned, Outcome::kCharging,
                          fmt::format("a charge at the dock {}–{} to about {:.0f} %{} ({})",
                                      zone_.format_clock(c.start).substr(0, 5), zone_.format_clock(c.end),
                                      c.target * 100, c.before ? ", before task " + *c.before : "", why));
  dispatcher_->follow_charges(std::move(charges));
  charging_->drift().planned(answer.points);
}

void Executor::apply_schedule(const std::vector<TaskId>& ids, const PlannedAnswer& answer, const std::string& why) {
  const schedule::Schedule& s = answer.result.schedule;
  apply_charges(ids, answer, why);
  std::vector<TaskId> planned;
  for (const schedule::ScheduledTask& e : s.entries) {
    if (e.task >= ids.size()) continue;  // a charge
    const TaskId& id = ids[e.task];
    if (book_.finished(id)) continue;  // ended while a background solve was under way
    TaskRecord& r = book_.at(id);
    // The event log shows every (re)scheduling that moved a task, and why it happened.
    if (r.planned_start != e.start)
      book_.note(id, EventKind::kScheduled, Outcome::kScheduled,
                 fmt::format("planned start {} ({}: position {} of {})", zone_.format_clock(e.start), why,
                             planned.size() + 1, s.entries.size()));
    r.planned_start = e.start;
    r.planned_end = e.end;
    if (r.dropped_for_now) {
      book_.note(id, EventKind::kReOffered, Outcome::kScheduled,
                 fmt::format("fits again after its drop: planned start {} ({})", zone_.format_clock(e.start), why));
      r.dropped_for_now.reset();
      dispatcher_->undefer(id);
    }
    planned.push_back(id);  // a task being waited for too: kick() reconsiders it
  }
  dispatcher_->follow_schedule(std::move(planned));
  publish_stops();
  std::vector<TaskId> dropped_now;  // for the fleet, which may find them room on another robot
  for (const schedule::DroppedTask& d : s.dropped) {
    if (d.task >= ids.size()) continue;  // a charge
    const TaskId& id = ids[d.task];
    if (book_.finished(id)) continue;
    if (run_ && run_->waiting() && run_->id() == id) end_wait();
    TaskRecord& r = book_.at(id);
    r.planned_start.reset();
    r.planned_end.reset();
    // Dropped for now: offered again at every reschedule while its window can still be met.
    // While the robot must charge, what does not fit does not fit for the charge.
    // So does what the battery left out (planned charging).
    const bool for_battery =
        std::find(answer.for_battery.begin(), answer.for_battery.end(), d.task) != answer.for_battery.end();
    const Outcome outcome = charging_->low() || for_battery ? Outcome::kCharging : drop_outcome(d.cause);
    const std::string reason =
        charging_->low()
            ? fmt::format("while the robot charges (about {} more): {}", duration_text(charging_->time_to_charge()),
                          d.reason)
        : for_battery ? (answer.refused ? d.reason : "no room beside the charge the battery needs: " + d.reason)
                      : d.reason;
    if (r.state != TaskState::kQueued) book_.transition(id, TaskState::kQueued, outcome, reason);
    if (!r.dropped_for_now) {
      book_.note(id, EventKind::kDroppedForNow, outcome, reason);
      dropped_now.push_back(id);
      // When its window can no longer be met it is dropped for good, whatever else happens.
      clock_.schedule_at(r.task.window->deadline - r.remaining() + milliseconds(1),
                         [this] { (void)reoffer_deferred(); });
    }
    r.dropped_for_now = std::make_pair(outcome, reason);
    dispatcher_->defer(id);
  }
  if (!dropped_now.empty() && dropped_) dropped_(dropped_now);
}

}  // namespace rondo::exec
