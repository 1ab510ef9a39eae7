// The executor's assumptions and opportunities (MISSION.md §5, docs/executor.md): every schedule
// records what it rests on (the doors of the rooms it enters open, its edges passable); a door seen
// closed that a planned task needs blocks that task (it waits as an opportunity while its deadline
// allows) and the rest is rescheduled at once, while the robot moves; a door seen open lets the
// task waiting for it run at once, interrupting the running task, when every planned task still
// fits around it.
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <optional>

#include "assumptions.h"
#include "deliveries.h"
#include "dispatcher.h"
#include "door_models.h"
#include "opportunities.h"
#include "rondo/exec/executor.h"
#include "rondo/store/observations.h"
#include "scheduling.h"
#include "spec_tasks.h"
#include "task_run.h"

namespace rondo::exec {
namespace {

constexpr double kLikelyOpen = 0.5;  // a retry goes when the door is at least this likely open

// Two tasks that stand or fall together: the halves of one delivery job, or one after the other.
bool linked(const Task& a, const Task& b) {
  if (a.delivery && b.delivery && a.delivery->job == b.delivery->job) return true;
  const auto after = [](const Task& x, const Task& y) {
    return std::find(x.after.begin(), x.after.end(), y.id) != x.after.end();
  };
  return after(a, b) || after(b, a);
}

std::string joined(const std::vector<TaskId>& ids) {
  if (ids.empty()) return "nothing";
  std::string s;
  for (const TaskId& id : ids) s += (s.empty() ? "" : ", ") + id;
  return s;
}

}  // namespace

// Where a door was seen from, for the event log: the robot's node, or the building's sensor.
std::string Executor::seen_from(const Observation& seen) const {
  return seen.source.empty() ? map_.node(robot_.location()).name : seen.source;
}

bool Executor::blocked(const TaskId& id) const { return opportunities_->blocked(id); }

std::optional<double> Executor::door_open_probability(const std::string& door, Time t) const {
  return door_models_.probability(door, t);
}

std::vector<std::string> Executor::door_names() const { return door_models_.doors(); }

// The task waits for its door (kept in its stored progress): it fails at its latest start unless
// the door is seen open first, and is retried when the door is likely open.
void Executor::wait_for_door(const TaskId& id, const DoorWait& wait) {
  const TaskRecord& r = book_.at(id);
  const Time latest = r.task.window->deadline - r.remaining();
  const std::uint64_t serial =
      opportunities_->block(id, {.door = wait.door, .since = wait.since, .seen_at = wait.seen_at});
  book_.set_door_wait(id, wait);
  clock_.schedule_at(std::max(clock_.now(), latest) + milliseconds(1),
                     [this, id, serial] { blocked_until_deadline(id, serial); });
  place_retry(id, wait.door, latest, serial);
}

void Executor::unblock(const TaskId& id) {
  opportunities_->unblock(id);
  book_.set_door_wait(id, std::nullopt);
}

// With a learned door model, a blocked task does not only wait to be passed by: it is offered to
// the scheduler again at the first time its door is likely open, if that is before its latest start.
void Executor::place_retry(const TaskId& id, const std::string& door, Time latest, std::uint64_t serial) {
  const Time now = clock_.now();
  const std::optional<Time> at = door_models_.next_likely_open(door, now, latest, kLikelyOpen);
  if (!at) return;
  book_.note(id, EventKind::kRetryPlanned, Outcome::kOpportunity,
             fmt::format("{} is likely open at {} (p = {:.2f}, learned from {} observations): offered to the "
                         "scheduler again then",
                         door, zone_.format_clock(*at), door_models_.probability(door, *at).value_or(0),
                         door_models_.samples(door)));
  clock_.schedule_at(*at, [this, id, serial] { retry_blocked(id, serial); });
}

void Executor::retry_blocked(const TaskId& id, std::uint64_t serial) {
  const Blocked* b = opportunities_->find(id);
  const TaskRecord* r = book_.find(id);
  if (b == nullptr || b->serial != serial || r == nullptr || r->state != TaskState::kQueued) return;
  const std::string door = b->door;
  // The tasks waiting with it (the other half of its job) go back with it.
  std::vector<TaskId> ids{id};
  for (const TaskId& other : opportunities_->waiting_for(door))
    if (const TaskRecord* o = book_.find(other); other != id && o != nullptr && linked(o->task, r->task))
      ids.push_back(other);
  for (const TaskId& t : ids) unblock(t);
  ++assumption_stats_.retries;
  reschedule(ids, fmt::format("retry of {}: {} likely open", joined(ids), door));
  kick();
}

void Executor::after_schedule(const std::string& why) {
  const Time now = clock_.now();
  std::vector<PlannedStop> stops;
  const auto stop_of = [&](const TaskRecord& r, Time until) {
    const Task& t = r.task;
    const map::NodeIndex start = t.start_node.empty() ? robot_.location() : *map_.find_node(t.start_node);
    stops.push_back({.task = t.id, .start = start,
                     .end = t.end_node.empty() ? start : *map_.find_node(t.end_node), .until = until});
  };
  // The running task rests on its way there until it arrives; then it is inside.
  if (run_ && !run_->waiting() && !run_->acting_since()) {
    const TaskRecord& r = book_.at(run_->id());
    stop_of(r, r.planned_end.value_or(now + r.remaining()));
  }
  for (const TaskId& id : dispatcher_->on_demand()) stop_of(book_.at(id), now + book_.at(id).remaining());
  if (run_ && run_->waiting()) stop_of(book_.at(run_->id()), book_.at(run_->id()).planned_end.value_or(now));
  for (const TaskId& id : dispatcher_->planned()) {
    const TaskRecord& r = book_.at(id);
    if (run_ && run_->waiting() && run_->id() == id) continue;
    stop_of(r, r.planned_end.value_or(r.task.window->deadline));
  }
  assumptions_ = assumption_map_->for_plan(robot_.location(), stops);
  if (!assumptions_.empty())
    book_.note_schedule(EventKind::kAssumptions, Outcome::kNone, fmt::format("{}: {}", why, describe(assumptions_, zone_)));
  note_look_alikes();
  if (!broken_ || (run_ && run_->stopping())) return;  // a stopping task: the schedule after it says it
  std::vector<TaskId> now_planned = dispatcher_->planned();
  ++assumption_stats_.reschedules;
  book_.note_schedule(EventKind::kRescheduled, Outcome::kAssumptionBroken,
                      fmt::format("{}; the plan was {}; it is now {}", *broken_, joined(plan_before_break_),
                                  joined(now_planned)));
  broken_.reset();
}

// Jobs whose objects look the same are never on board together (the scheduler's rule): the event
// log says so whenever the set of such jobs changes, since the plan's order follows from it.
void Executor::note_look_alikes() {
  std::map<std::string, std::vector<std::string>> jobs;  // appearance -> jobs to do or on board
  const auto add = [&](const std::string& appearance, const std::string& job) {
    if (appearance.empty()) return;
    std::vector<std::string>& j = jobs[appearance];
    if (std::find(j.begin(), j.end(), job) == j.end()) j.push_back(job);
  };
  for (const OnBoard& o : on_board()) add(o.appearance, o.job);
  for (const TaskId& id : dispatcher_->planned())
    if (const auto& d = book_.at(id).task.delivery) add(d->appearance, d->job);
  std::string text;
  for (const auto& [appearance, list] : jobs) {
    if (list.size() < 2) continue;
    std::string names;
    for (const std::string& j : list) names += (names.empty() ? "" : ", ") + j;
    text += fmt::format("{}jobs {} carry objects that look the same ('{}'): never on board together, so each is "
                        "dropped before the next is picked up",
                        text.empty() ? "" : "; ", names, appearance);
  }
  if (text == look_alikes_) return;
  look_alikes_ = text;
  if (!text.empty()) book_.note_schedule(EventKind::kLookAlike, Outcome::kNone, text);
}

// A task that can wait for a door: a standard one, not final, not blocked already, and not running
// past the point of stopping (acting inside the room, or on its way but not interruptible now).
// An on-demand task has no window to wait in: navigation deals with its door.
bool Executor::can_wait(const TaskId& id) const {
  if (!book_.contains(id) || blocked(id)) return false;
  const TaskRecord& r = book_.at(id);
  if (is_final(r.state) || r.task.kind != TaskKind::kStandard || !r.task.window) return false;
  if (run_ && run_->id() == id && !run_->waiting()) return !run_->acting_since() && interruptible_now();
  return true;
}

void Executor::door_seen_closed(const Observation& seen) {
  const Time now = clock_.now();
  door_models_.observe(seen.where, seen.when, false);
  std::vector<std::pair<TaskId, Assumption>> hit;
  for (const Assumption& a : assumptions_) {
    if (a.kind != Assumption::Kind::kDoorOpen || a.what != seen.where || a.until < now) continue;
    if (!can_wait(a.task)) continue;
    if (std::none_of(hit.begin(), hit.end(), [&](const auto& h) { return h.first == a.task; }))
      hit.emplace_back(a.task, a);
  }
  if (hit.empty()) return;
  // A job's halves wait together: a drop whose pickup waits, and a pickup whose drop waits (the
  // object is not fetched while it cannot be delivered; one already on board stays on board).
  std::vector<TaskId> live = dispatcher_->planned();
  if (run_ && !run_->acting_since()) live.push_back(run_->id());
  const auto hit_has = [&](const TaskId& id) {
    return std::any_of(hit.begin(), hit.end(), [&](const auto& h) { return h.first == id; });
  };
  for (std::size_t i = 0; i < hit.size(); ++i) {
    const Assumption why = hit[i].second;
    const Task& blocked_task = book_.at(hit[i].first).task;
    for (const TaskId& id : live) {
      if (hit_has(id)) continue;
      const Task& t = book_.at(id).task;
      if (linked(t, blocked_task) && can_wait(id)) hit.emplace_back(id, why);
    }
  }
  ++assumption_stats_.broken;
  const std::string node = seen_from(seen);
  plan_before_break_.clear();
  if (run_ && !run_->waiting()) plan_before_break_.push_back(run_->id());
  for (const TaskId& id : dispatcher_->planned())
    if (std::find(plan_before_break_.begin(), plan_before_break_.end(), id) == plan_before_break_.end())
      plan_before_break_.push_back(id);
  std::vector<TaskId> ids;
  bool stopping_run = false;
  std::optional<std::string> running_reason;  // the running task is one of them
  for (const auto& [id, a] : hit) {
    ids.push_back(id);
    TaskRecord& r = book_.at(id);
    const Time latest = r.task.window->deadline - r.remaining();
    dispatcher_->forget(id);
    r.planned_start.reset();
    r.planned_end.reset();
    const std::string reason =
        fmt::format("assumption '{} {}' (until {}) broken: {} seen closed from {} at {}; it waits for the door "
                    "as an opportunity until its latest start {}",
                    to_string(a.kind), a.what, zone_.format_clock(a.until), seen.where, node,
                    zone_.format_clock(now), zone_.format_clock(latest));
    book_.note(id, EventKind::kBlocked, Outcome::kAssumptionBroken, reason);
    wait_for_door(id, {.door = seen.where, .since = now, .seen_at = node});
    if (run_ && run_->id() == id) running_reason = reason;
  }
  broken_ = fmt::format("assumption broken: {} seen closed from {} at {}: {} {}", seen.where, node,
                        zone_.format_clock(now), joined(ids),
                        ids.size() == 1 ? "waits as an opportunity" : "wait as opportunities");
  // Every task of the break is blocked before the running one stops (its end may reschedule at once).
  if (running_reason) {
    if (run_->waiting()) {
      const TaskId id = run_->id();
      end_wait();
      book_.transition(id, TaskState::kQueued, Outcome::kAssumptionBroken, *running_reason);
    } else {  // on its way and interruptible (can_wait)
      stopping_run = true;
      preempt_for(Outcome::kAssumptionBroken, fmt::format("its door {} was seen closed", seen.where), {});
    }
  }
  if (stopping_run) return;  // the task's end reschedules the rest (without it)
  reschedule({}, "door " + seen.where + " seen closed");
  kick();
}

bool Executor::opportunity_fits(const TaskId& id, bool interrupt, const std::vector<TaskId>& with,
                                std::string& why_not) {
  const TaskRecord& r = book_.at(id);
  const Time now = clock_.now();
  // Where and when the robot would take it: now from here (the running task goes back to the
  // queue), or once the running task and the on-demand ones are done.
  auto [from, at] = interrupt ? std::pair{robot_.location(), now} : free_at();
  const map::NodeIndex start = task_place(building_.spec_tasks.get(), map_, r, from, at);
  const Duration travel = task_travel(travel_, building_.spec_tasks.get(), map_, r, from, at);
  const Time begins = std::max(at + travel, r.task.window->release);
  const Time ends = begins + r.remaining();
  if (travel >= kUnreachable || ends > r.task.window->deadline) {
    why_not = fmt::format("{} itself would end at {}, after its deadline {}", id, zone_.format_clock(ends),
                          zone_.format_clock(r.task.window->deadline));
    return false;
  }
  PendingTasks pending;
  if (interrupt && running_standard()) pending.ids.push_back(run_->id());
  const std::vector<TaskId>* lists[] = {&dispatcher_->planned(), &with};
  for (const std::vector<TaskId>* list : lists)
    for (const TaskId& p : *list)
      if (p != id && std::find(pending.ids.begin(), pending.ids.end(), p) == pending.ids.end())
        pending.ids.push_back(p);
  if (pending.ids.empty()) return true;
  pending.old_count = pending.first_reoffered = pending.ids.size();
  std::vector<OnBoard> load = interrupt ? on_board() : on_board_when_free();
  if (const auto& d = r.task.delivery) {
    if (d->role == DeliveryRole::kDrop)
      std::erase_if(load, [&](const OnBoard& o) { return o.job == d->job; });
    else
      load.push_back({.job = d->job, .object = d->object, .appearance = d->appearance, .load = d->load,
                      .picked_up_by = id});
  }
  std::mt19937_64 rng(options_.seed);  // a trial: the executor's own draws stay as they were
  const ScheduleInputs in{.map = map_,
                          .travel = travel_,
                          .book = book_,
                          .zone = zone_,
                          .scheduler = *scheduler_,
                          .polls = options_.scheduler_polls,
                          .rng = rng,
                          .capacity = options_.capacity,
                          .on_board = std::move(load),
                          .risk_alpha = options_.risk_alpha,
                          .specs = building_.spec_tasks.get(),
                          .speed = building_.speeds.factor(options_.robot_name)};
  const map::NodeIndex end = r.task.end_node.empty() ? start : *map_.find_node(r.task.end_node);
  refresh_learned_durations(pending.ids);
  auto solved = schedule_pending(in, pending, end, ends, std::nullopt);
  if (!solved) {
    why_not = solved.error().message;
    return false;
  }
  stats_.schedules += solved->attempts;
  if (solved->outcome != schedule::TryScheduleOutcome::kAllScheduled || !solved->schedule.dropped.empty()) {
    std::vector<TaskId> lost;
    for (const schedule::DroppedTask& d : solved->schedule.dropped) lost.push_back(pending.ids[d.task]);
    why_not = fmt::format("taking it first leaves no room for {}", lost.empty() ? "the planned tasks" : joined(lost));
    return false;
  }
  return true;
}

void Executor::door_seen_open(const Observation& seen) {
  door_models_.observe(seen.where, seen.when, true);
  std::vector<TaskId> waiting;
  for (const TaskId& id : opportunities_->waiting_for(seen.where)) {
    if (book_.finished(id)) {
      unblock(id);
      continue;
    }
    waiting.push_back(id);
  }
  if (waiting.empty()) return;
  const std::string node = seen_from(seen);
  const std::string when = zone_.format_clock(clock_.now());
  const bool interrupt = running_standard() && interruptible_now() && !run_->acting_since();
  // The first waiting task that fits is taken now; the others (a drop behind its pickup, a task
  // that would break a deadline first) go back to the scheduler, which plans them as new tasks.
  std::optional<TaskId> taken;
  std::vector<TaskId> back;
  for (const TaskId& id : waiting) {
    unblock(id);
    const Task& t = book_.at(id).task;
    bool behind = std::any_of(t.after.begin(), t.after.end(), [&](const TaskId& a) { return !book_.finished(a); });
    if (t.delivery && t.delivery->role == DeliveryRole::kDrop)
      if (const Deliveries::Job* job = deliveries_->job(t.delivery->job); job && job->pickup)
        behind = behind || !book_.finished(*job->pickup);
    std::string why_not;
    if (taken || behind) {
      back.push_back(id);
    } else if (opportunity_fits(id, interrupt, waiting, why_not)) {
      taken = id;
    } else {
      ++assumption_stats_.opportunities_declined;
      book_.note(id, EventKind::kOpportunityDeclined, Outcome::kOpportunityDeclined,
                 fmt::format("{} seen open from {} at {}, but {}; offered to the scheduler again", seen.where, node,
                             when, why_not));
      back.push_back(id);
    }
  }
  if (!taken) {
    reschedule(back, "door " + seen.where + " seen open");
    return kick();
  }
  ++assumption_stats_.opportunities_taken;
  dispatcher_->queue_on_demand(*taken);  // it runs next, before the planned tasks
  const std::string then =
      interrupt ? fmt::format("interrupts {}", run_->id())
                : (run_ && !run_->waiting() ? fmt::format("runs right after {}", run_->id()) : std::string("runs now"));
  book_.note(*taken, EventKind::kOpportunity, Outcome::kOpportunityTaken,
             fmt::format("{} seen open from {} at {}: {}; every planned task still fits after it", seen.where, node,
                         when, then));
  if (interrupt) return preempt_for(Outcome::kOpportunityTaken, "interrupted for the opportunity " + *taken, back);
  reschedule(back, "opportunity " + *taken + " runs next");
  kick();
}

void Executor::blocked_until_deadline(const TaskId& id, std::uint64_t serial) {
  const Blocked* b = opportunities_->find(id);
  if (b == nullptr || b->serial != serial || book_.finished(id) || book_.at(id).state != TaskState::kQueued) return;
  const std::string reason =
      fmt::format("{} seen closed from {} at {} and not seen open since: its deadline {} can no longer be met", b->door,
                  b->seen_at, zone_.format_clock(b->since), zone_.format_clock(book_.at(id).task.window->deadline));
  unblock(id);
  ++assumption_stats_.failed_blocked;
  book_.transition(id, TaskState::kFailed, Outcome::kAssumptionBroken, reason);
  reschedule({}, "task " + id + " failed");  // a letter on board gets its way back
  kick();
}

}  // namespace rondo::exec
