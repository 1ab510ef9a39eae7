// The executor running tasks: what to do next (the dispatcher's decisions carried out), a task's
// run from start to end, the executor's own trips to the dock, and preemption.
#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "charging.h"
#include "dispatcher.h"
#include "found_blocked.h"
#include "rondo/exec/executor.h"
#include "task_run.h"
#include "traffic_link.h"

namespace rondo::exec {

void Executor::kick() {
  if (run_) {
    if (!run_->waiting()) return;  // a task navigates or acts: it goes on
    return requeue_waiting(Outcome::kScheduleChanged, "waiting interrupted: the schedule changed");
  }
  if (trip_) return trip_->halt();  // trip_ended() looks again
  next();
}

void Executor::requeue_waiting(Outcome outcome, const std::string& reason) {
  const TaskId id = run_->id();
  end_wait();
  book_.transition(id, TaskState::kQueued, outcome, reason);
  dispatcher_->put_first_in_plan(id);
  next();
}

void Executor::next() {
  struct Traffic {  // whatever next() decides, the traffic manager knows whether the robot is
    Executor& e;    // parked, and the others where it plans to stop
    ~Traffic() {
      e.update_parked();
      e.publish_stops();
    }
  } traffic{*this};
  if (run_ || trip_ || robot_.busy() || in_fault_) return;  // a fault: on_ready() comes back here
  if (look_again_ != 0) clock_.cancel(look_again_);
  look_again_ = 0;
  if (out_of_service_) return go_to_dock(JourneyPurpose::kOutOfService);  // nothing new starts
  if (must_charge()) return charge();        // below the battery's hard threshold
  const Time now = clock_.now();
  const map::NodeIndex here = robot_.location();
  for (;;) {
    Decision d = dispatcher_->next(here, now);
    switch (d.kind) {
      case Decision::Kind::kRun:
        if (charge_first(d.task)) return charge();
        return start_run(d.task, std::nullopt);
      case Decision::Kind::kWait:
        if (charge_first(d.task)) return charge();
        if (d.traffic_delay > Duration{0}) {
          ++building_.deferrals.count;
          building_.deferrals.total += d.traffic_delay;
        }
        return start_run(d.task, d.until, d.reason);
      case Decision::Kind::kFail:
        book_.transition(d.task, TaskState::kFailed, d.outcome, d.reason);
        reschedule({}, "task " + d.task + " failed");
        continue;
      case Decision::Kind::kDock:
        if (free_) free_();
        return go_to_dock(JourneyPurpose::kDock);
      case Decision::Kind::kIdleUntil:
        if (free_) free_();
        return look_again_at(d.until);
      case Decision::Kind::kCharge:
        // The battery already holds what the charge is for (full, say): nothing to charge. Started,
        // it would end at once, and the reschedule after it could plan it again at the same moment,
        // again and again (examples/battery, seed 14, 90 days: a second of simulated time a round).
        if (charging_->level() >= std::max(d.level, charging_->resume_level())) continue;
        charging_->start_planned(d.until, d.length, d.level);
        return charge();
      case Decision::Kind::kStay:
        if (reoffer_for_battery()) continue;
        return;
    }
  }
}

// Planned charging: a task the battery cannot afford now (the way there, its work and the way back
// to the charger, above the reserve and the margin) runs after a charge to what it needs, and
// stays first in its queue. The plan's predictions were made earlier and may have missed (longer
// actions, a night shut out); this is the last look before the robot sets out. One that even a
// full battery could not afford runs at once.
bool Executor::charge_first(const TaskId& id) {
  const std::optional<Charging::Short> short_of = charging_->short_for(id, robot_.location());
  if (!short_of || short_of->needed > 1) return false;
  const Time now = clock_.now();
  if (book_.at(id).task.kind == TaskKind::kOnDemand)
    dispatcher_->put_first_on_demand(id);
  else
    dispatcher_->put_first_in_plan(id);
  book_.note(id, EventKind::kWaitsForTheCharge, Outcome::kCharging, short_of->why);
  const double hours = std::max(0.0, charging_->estimator().hours_to_charge(charging_->level(), short_of->needed));
  const Duration on_charger = from_seconds(hours * 3600) + minutes(1);
  charging_->start_planned(now + travel_.travel(robot_.location(), options_.dock, now) + on_charger, on_charger,
                           short_of->needed);
  reschedule({}, "charging for task " + id);
  return true;
}

void Executor::start_run(const TaskId& id, std::optional<Time> wait_until, std::string behind) {
  std::optional<EarlyWait> wait;
  if (wait_until) {
    wait = EarlyWait{.until = *wait_until, .behind = std::move(behind)};
    if (booking_) {  // planning around each other: the others' stops are read again when it is time
      wait->longer = [this, id] { return dispatcher_->put_off_now(id, robot_.location(), clock_.now()); };
      wait->set_out = [this] { publish_stops(); };
    }
  }
  run_ = std::make_unique<TaskRun>(steps_, id, std::move(wait), [this](TaskEnd e) { run_ended(std::move(e)); });
  // An on-demand task runs now: the rest of the day is planned around it.
  if (run_->task().kind == TaskKind::kOnDemand) reschedule({}, "on-demand task " + id + " runs now");
  run_->start();
}

void Executor::run_ended(TaskEnd e) {
  const TaskId id = run_->id();
  const Time run_since = run_->run_since();
  retire_run();
  const TaskRecord& r = book_.at(id);
  stats_.busy += clock_.now() - run_since;  // this run's, not the task's span since its first run
  std::vector<TaskId> again = std::exchange(after_preempt_, {});
  const bool on_demand = r.task.kind == TaskKind::kOnDemand;
  if (std::function<void(const TaskId&)> handed = std::exchange(handing_back_, {}); handed && e.requeue) {
    hand_back(id, e, std::move(handed));
    if (!again.empty()) reschedule(std::move(again), "after handing back " + id);
    return next();
  }
  if (e.requeue && e.edge && !hold_back(id, *e.edge, e.not_before)) {
    e.requeue = false;
    e.state = TaskState::kFailed;
    e.reason += on_demand ? "; the way is not likely passable again within its patience"
                          : "; the way is not likely passable again before its latest start";
  }
  if (e.requeue && on_demand && (e.edge || e.outcome == Outcome::kCharging)) {
    if (e.edge)
      hold_on_demand(id, e.outcome, e.reason);
    else
      requeue_on_demand(id, e.outcome, e.reason);  // it runs first once charged
    if (!again.empty()) reschedule(std::move(again), "after holding " + id);
    return next();
  }
  if (e.requeue) {
    // Preempted: the task keeps its id and goes back to the queue, to be scheduled again.
    requeue_preempted(id, e.outcome, e.reason);
    if (book_.at(id).state == TaskState::kQueued) {
      if (preempted_ && e.outcome == Outcome::kPreemptedOnDemand)
        clock_.schedule_after(Duration{0}, [call = preempted_, id] { call(id); });  // to the fleet's pool
      else
        again.push_back(id);
    }
    if (!again.empty()) reschedule(std::move(again), "after preempting " + id);
    return next();
  }
  book_.transition(id, e.state, e.outcome, e.reason);
  log_battery();
  if (e.state == TaskState::kCancelled) cancel_job_of(id, e.reason);
  if (e.state == TaskState::kFailed || e.state == TaskState::kCancelled || !again.empty())
    reschedule(std::move(again), "task " + id + " " + to_string(e.state));
  next();
}

void Executor::end_wait() {
  run_->abandon_wait();
  retire_run();
}

void Executor::retire_run() { retired_runs_.push_back(std::move(run_)); }
void Executor::retire_trip() { retired_steps_.push_back(std::move(trip_)); }

void Executor::go_to_dock(JourneyPurpose purpose) {
  if (robot_.location() == options_.dock) return;
  if (const std::optional<Time> closed = charging_->way_home_closed_until(); closed && clock_.now() < *closed)
    return look_again_at(*closed);
  start_trip(purpose, options_.dock);
}

void Executor::start_trip(JourneyPurpose purpose, map::NodeIndex to) {
  // Its monitor's end is its own (NavigateStep::overran): the overrun hook is a task's.
  trip_ = std::make_unique<NavigateStep>(steps_,
                                         StepHooks{.ended = [this](StepEnd e) { trip_ended(std::move(e)); },
                                                   .overrun = [](Outcome, const std::string&) {}},
                                         purpose, std::nullopt, to);
  trip_->start();
}

// How a journey of the executor's own ends (docs/executor.md, "Journeys"): arrived, the executor
// goes on; stopped for something else to do, a `stopped` robot event; a way found blocked (before
// leaving, or an edge that failed and is not worth trying again now) under the `wait` policy, a
// `waits` event and the executor looks again when the way is likely passable (with the battery
// planned, when the way home is likely open again: Charging::retry_way_home); otherwise a `gave
// up` event, and it looks again after a slot.
void Executor::trip_ended(StepEnd e) {
  const std::string journey = fmt::format("the journey to {} ({})", map_.node(trip_->target()).name, trip_->errand());
  retire_trip();
  const Time now = clock_.now();
  const std::string here = map_.node(robot_.location()).name;
  switch (e.status) {
    case StepEnd::Status::kDone: return next();
    case StepEnd::Status::kHalted:
      book_.note_robot(options_.robot_name, EventKind::kStopped, Outcome::kScheduleChanged,
                       fmt::format("{} stopped at {}: the executor looks again at what to do", journey, here));
      return next();
    case StepEnd::Status::kBlocked:
    case StepEnd::Status::kFailed: break;
  }
  if (options_.battery_planning && e.edge && !e.not_before)
    return look_again_at(charging_->retry_way_home(*e.edge));
  std::optional<Time> again = e.not_before;
  if (e.status == StepEnd::Status::kBlocked && !again) {
    if (const std::optional<std::pair<Time, double>> open = passable_again(*e.edge, now + hours(24))) {
      again = open->first;
      e.reason += fmt::format("; {} is likely passable again at {} (p = {:.2f})", map_.edge(*e.edge).id,
                              zone_.format_clock(open->first), open->second);
    } else {
      e.reason += fmt::format("; {} is not likely passable again within a day", map_.edge(*e.edge).id);
    }
  }
  if (again) {
    book_.note_robot(options_.robot_name, EventKind::kWaits, Outcome::kNoRouteNow,
                     fmt::format("{} waits at {}: {}; it looks again at {}", journey, here, e.reason,
                                 zone_.format_clock(*again)));
    return look_again_at(*again);
  }
  const Time later = now + (e.status == StepEnd::Status::kBlocked ? hours(24) : options_.slot_width);
  book_.note_robot(options_.robot_name, EventKind::kGaveUp, e.outcome,
                   fmt::format("{} gave up at {}: {}; it looks again at {}", journey, here, e.reason,
                               zone_.format_clock(later)));
  look_again_at(later);
}

void Executor::look_again_at(Time at) {
  if (look_again_ != 0) clock_.cancel(look_again_);
  look_again_ = clock_.schedule_at(at, [this] {
    look_again_ = 0;
    kick();
  });
}

void Executor::preempt_for(Outcome outcome, const std::string& reason, std::vector<TaskId> then_schedule) {
  if (!run_ || run_->waiting()) return;
  after_preempt_.insert(after_preempt_.end(), then_schedule.begin(), then_schedule.end());
  if (run_->stopping()) return;  // it ends anyway; the new tasks are scheduled then
  run_->stop(TaskRun::Stop::kPreempt, outcome, reason);
}

bool Executor::hold_back(const TaskId& id, map::EdgeIndex edge, std::optional<Time> leave_at) {
  if (leave_at) {  // the navigation found a later departure that arrives sooner; its reason says so
    book_.set_not_before(id, *leave_at);
    return true;
  }
  const std::optional<std::pair<Time, double>> open =
      passable_again(edge, book_.at(id).latest_start(options_.on_demand_patience));
  if (!open) return false;
  book_.set_not_before(id, open->first);
  book_.note(id, EventKind::kRetryPlanned, Outcome::kNoRouteNow,
             fmt::format("{} is likely passable again at {} (p = {:.2f}): not scheduled before then",
                         map_.edge(edge).id, zone_.format_clock(open->first), open->second));
  return true;
}

std::optional<std::pair<Time, double>> Executor::passable_again(map::EdgeIndex edge, Time until) const {
  return exec::passable_again(models_, planner_, options_.slot_width, edge, clock_.now(), until);
}

void Executor::hold_on_demand(const TaskId& id, Outcome outcome, const std::string& reason) {
  requeue_on_demand(id, outcome, reason);
  clock_.schedule_at(*book_.at(id).not_before, [this] { on_demand_due(); });
}

void Executor::requeue_on_demand(const TaskId& id, Outcome outcome, const std::string& reason) {
  book_.transition(id, TaskState::kQueued, outcome, reason + "; back in the on-demand queue");
  dispatcher_->put_first_on_demand(id);  // it came before the others waiting
}

void Executor::on_demand_due() {
  if (!give_way_to_on_demand()) kick();
}

void Executor::hand_back(const TaskId& id, const TaskEnd& e, std::function<void(const TaskId&)> handed) {
  if (book_.at(id).task.kind == TaskKind::kOnDemand)
    book_.transition(id, TaskState::kQueued, e.outcome, e.reason + "; back in the fleet's pool");
  else
    requeue_preempted(id, e.outcome, e.reason);  // queued, or failed when its window no longer allows it
  if (book_.at(id).state != TaskState::kQueued) return;
  book_.at(id).dropped_for_now.reset();
  clock_.schedule_after(Duration{0}, [handed = std::move(handed), id] { handed(id); });
}

void Executor::requeue_preempted(const TaskId& id, Outcome outcome, const std::string& reason) {
  const TaskRecord& r = book_.at(id);
  if (r.task.kind == TaskKind::kStandard && clock_.now() + r.remaining() <= r.task.window->deadline) {
    book_.transition(id, TaskState::kQueued, outcome, reason + "; back in the queue");
    return;
  }
  book_.transition(id, TaskState::kFailed, outcome, reason + "; its window no longer allows it");
}

}  // namespace rondo::exec
