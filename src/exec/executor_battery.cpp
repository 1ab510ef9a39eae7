// The executor and the battery (docs/executor.md, "Battery"): readings at every robot callback
// and before every command (BatteryWatch, which learns the battery's costs from them), and the
// hard threshold: below it the robot goes to charge at the next interruptible moment, whatever the
// schedule says, and starts nothing new until the battery is back at the resume level.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "battery_watch.h"
#include "charge_planning.h"
#include "dispatcher.h"
#include "rondo/exec/executor.h"
#include "rondo/map/map_geometry.h"
#include "task_run.h"
#include "text.h"

namespace rondo::exec {
namespace {

constexpr int kWayHomeDoublings = 4;  // a closed way home is tried again after at most 2^4 slots

// A state of charge for people: "14.9 %".
std::string percent(double level) { return fmt::format("{:.1f} %", level * 100); }

}  // namespace

void Executor::read_battery() { battery_->read(clock_.now(), robot_.battery(), robot_.charging()); }

double Executor::resume_level() const {
  return options_.battery_resume > 0 ? options_.battery_resume : options_.battery_reserve;
}

bool Executor::below_threshold() const {
  if (battery_->level() < home_level()) return true;
  return options_.battery_threshold > 0 && battery_->level() < options_.battery_threshold;
}

double Executor::home_level() const {
  if (!options_.battery_planning) return 0;
  const double home_hours = way_home_hours();
  const BatteryPrediction p = way_home(home_hours);
  // Readings come between edges: one more edge away from the dock must still leave the way back.
  double next_edge = 0;
  for (const map::EdgeIndex e : map_.out_edges(robot_.location())) next_edge = std::max(next_edge, edge_cost(e));
  return options_.battery_reserve + p.mean + next_edge + margin_over(p, home_hours);
}

// The margin the plans keep (ChargePlan): `battery_margin` standard deviations of the prediction,
// from the rates' standard error and what plans missed per hour (PlanDrift) over `hours`.
double Executor::margin_over(const BatteryPrediction& p, double hours) const {
  return options_.battery_margin *
         std::sqrt(p.standard_error * p.standard_error + drift_->variance_per_hour() * std::max(hours, 0.0));
}

double Executor::way_home_hours() const {
  return to_seconds(std::min<Duration>(travel_->travel(robot_.location(), options_.dock, clock_.now()), hours(24))) /
         3600.0;
}

BatteryPrediction Executor::way_home(double hours) const {
  const map::NodeIndex here = robot_.location();
  const double metres = here < metres_home_.size() && std::isfinite(metres_home_[here]) ? metres_home_[here] : 0;
  return battery_->estimator().predict({.metres = metres, .hours_moving = hours});
}

double Executor::edge_cost(map::EdgeIndex e) const {
  return battery_->estimator()
      .predict({.metres = map::edge_length(map_, e),
                .hours_moving = to_seconds(map::nominal_travel_time(map_, e)) / 3600.0})
      .mean;
}

Duration Executor::time_to_charge() const {
  const bool planned = planned_charge_ && !low_battery_;
  const double to = planned ? planned_charge_->target : resume_level();
  const double hours = battery_->estimator().hours_to_charge(battery_->level(), to);
  Duration d = hours > 0 ? from_seconds(hours * 3600) : Duration{0};
  if (planned) d = std::clamp(planned_charge_->until - clock_.now(), Duration{0}, d);
  return d;
}

double Executor::level_when_free(Time free) const {
  if (low_battery_) return resume_level();
  if (planned_charge_) return std::max(planned_charge_->target, battery_->level());
  double level = battery_->level();
  // The running task (and the on-demand ones before the plan) until then, counted as acting.
  if (run_ && !run_->waiting())
    level -= battery_->estimator().predict({.hours_acting = to_seconds(free - clock_.now()) / 3600.0}).mean;
  return std::clamp(level, 0.0, 1.0);
}

std::optional<Executor::BatteryShort> Executor::battery_short_for(const TaskId& id, map::NodeIndex from) const {
  if (!options_.battery_planning) return std::nullopt;
  const Task& task = book_.at(id).task;
  const map::NodeIndex start = task.start_node.empty() ? from : *map_.find_node(task.start_node);
  const map::NodeIndex end = task.end_node.empty() ? start : *map_.find_node(task.end_node);
  const auto finite = [](double m) { return std::isfinite(m) ? m : 0.0; };
  const auto hours_of = [](Duration d) { return to_seconds(std::min<Duration>(d, hours(24))) / 3600.0; };
  const Time now = clock_.now();
  const Duration there = travel_->travel(from, start, now);
  const Duration work = book_.at(id).remaining();
  const Duration back = travel_->travel(end, options_.dock, now + std::min<Duration>(there, hours(24)) + work);
  const BatteryPrediction p = battery_->estimator().predict(
      {.metres = finite(map::shortest_metres(map_, from)[start]) + (end < metres_home_.size() ? finite(metres_home_[end]) : 0),
       .hours_moving = hours_of(there) + hours_of(back),
       .hours_acting = hours_of(work)});
  const double hours = hours_of(there) + hours_of(work) + hours_of(back);
  const double left = battery_->level() - p.mean - drift_->per_hour() * hours;
  const double keep = options_.battery_reserve + margin_over(p, hours);
  if (left >= keep) return std::nullopt;
  return BatteryShort{.needed = battery_->level() + (keep - left),
                      .why = fmt::format("task {} would leave about {} after the way back to the charger, below the "
                                         "{} to keep",
                                         id, percent(std::max(left, 0.0)), percent(keep))};
}

void Executor::start_planned_charge(Time until, Duration length, double target) {
  const Time now = clock_.now();
  planned_charge_ = PlannedChargeRun{.since = now, .until = until, .length = length,
                                     .target = std::max(target, resume_level())};
  book_.note_robot("charging", Outcome::kCharging,
                   fmt::format("a planned charge: battery {} at {}, on the charger until {} or about {}",
                               percent(battery_->level()), map_.node(robot_.location()).name,
                               zone_.format_clock(until), percent(planned_charge_->target)));
}

bool Executor::charging_as_planned() {
  PlannedChargeRun& c = *planned_charge_;
  const Time now = clock_.now();
  if (!c.on_charger && robot_.location() == options_.dock) {
    // Reached the charger: it stays as long as planned, however long the way took.
    c.on_charger = true;
    c.until = std::max(c.until, now + c.length);
  }
  // The way to the charger takes longer than the charge itself: given up (the hard threshold stays).
  const bool missed = !c.on_charger && now >= c.until + c.length;
  if (battery_->level() < c.target && (c.on_charger ? now < c.until : !missed)) return true;
  if (missed)
    book_.note_robot("charge missed", Outcome::kCharging,
                     fmt::format("battery {}: the robot did not reach the charger in {} since {}: dispatch resumes",
                                 percent(battery_->level()), duration_text(now - c.since), zone_.format_clock(c.since)));
  else
    book_.note_robot("charged", Outcome::kCharging,
                     fmt::format("battery {} after the planned charge ({} since {}): dispatch resumes",
                                 percent(battery_->level()), duration_text(now - c.since), zone_.format_clock(c.since)));
  planned_charge_.reset();
  reschedule({}, "charged as planned");
  return false;
}

bool Executor::reoffer_for_battery() {
  const Time now = clock_.now();
  const bool waiting = std::any_of(dispatcher_->deferred.begin(), dispatcher_->deferred.end(), [&](const TaskId& id) {
    const TaskRecord& r = book_.at(id);
    return r.dropped_for_now && r.dropped_for_now->first == Outcome::kCharging;
  });
  if (!waiting || !options_.battery_planning) return false;
  if (now < battery_retry_) {
    look_again_at(battery_retry_);
    return false;
  }
  battery_retry_ = now + options_.slot_width;
  reschedule({}, fmt::format("battery {} on the charger: tasks dropped for the battery offered again",
                             percent(battery_->level())));
  return true;
}

// The way to the charger found closed while the battery is planned: every attempt costs some of
// the battery it is meant to save, and a robot shut out overnight (a door locked after hours) would
// spend the night trying. So the next trip waits twice as long after each failed one (a slot, then
// 2, 4, 8 and at most 16 slots; at once the longest when the battery above what the way home needs
// would not pay for two more attempts), and at least until the first slot start at which the
// snapshot's model (what time of day and week say, without the live model's memory of the last
// failure) holds the edge likely passable, looked for up to three days ahead.
Time Executor::retry_way_home(map::EdgeIndex edge) {
  const Time now = clock_.now();
  if (!way_home_closed_ || way_home_closed_->edge != edge) way_home_closed_ = WayHomeClosed{.edge = edge};
  WayHomeClosed& w = *way_home_closed_;
  ++w.failures;
  const double home_hours = way_home_hours();
  const BatteryPrediction home = way_home(home_hours);
  const double spare = battery_->level() - (options_.battery_reserve + home.mean + margin_over(home, home_hours));
  const int doublings = spare < 2 * edge_cost(edge) ? kWayHomeDoublings : std::min(w.failures - 1, kWayHomeDoublings);
  Time at = now + options_.slot_width * (1 << doublings);
  std::string learned;
  for (Time t = planner_->slot_start(now) + options_.slot_width; t <= now + hours(72); t += options_.slot_width) {
    const double p = offline_models_->outcome(edge, t).success_probability;
    if (p < kLikelyPassable) continue;
    if (t > at) {
      at = t;
      learned = fmt::format(", when it is likely passable again (p = {:.2f}, learned)", p);
    }
    break;
  }
  w.retry_at = at;
  book_.note_robot("way home closed", Outcome::kNoRouteNow,
                   fmt::format("battery {} at {}: {} failed on the way to the charger ({} in a row); the next try at "
                               "{}{}",
                               percent(battery_->level()), map_.node(robot_.location()).name, map_.edge(edge).id,
                               w.failures, zone_.format_clock(at), learned));
  return at;
}

void Executor::way_home_crossed(const EdgeAttempt& a) {
  if (!way_home_closed_) return;
  if ((a.succeeded() && a.edge == way_home_closed_->edge) || robot_.location() == options_.dock)
    way_home_closed_.reset();
}

BatteryFigures Executor::battery_figures() const {
  BatteryFigures f = battery_->figures();
  f.low_battery = low_battery_count_;
  return f;
}

void Executor::enter_low_battery() {
  low_battery_ = true;
  ++low_battery_count_;
  low_since_ = clock_.now();
  const double home = home_level();
  const std::string below =
      battery_->level() < home
          ? fmt::format("below {}, what the way to the charger needs to keep the reserve {}", percent(home),
                        percent(options_.battery_reserve))
          : fmt::format("below the hard threshold {}", percent(options_.battery_threshold));
  book_.note_robot("battery low", Outcome::kCharging,
                   fmt::format("battery {} at {}, {}: the robot goes to charge at the next interruptible moment and "
                               "starts nothing new until {} (about {} on the charger)",
                               percent(battery_->level()), map_.node(robot_.location()).name, below,
                               percent(resume_level()), duration_text(time_to_charge())));
}

void Executor::check_battery() {
  if (low_battery_ || !started_ || !below_threshold()) return;
  planned_charge_.reset();
  enter_low_battery();
  reschedule({}, "battery low");  // the plan starts after the charge (free_at)
  if (run_) return charge_now();
  if (!trip_) next();  // a trip goes to the dock anyway
}

void Executor::charge_now() {
  if (!run_ || run_->stopping()) return;
  const std::string why = fmt::format("the battery is below {}: the robot goes to charge",
                                      percent(options_.battery_threshold));
  if (run_->waiting()) return requeue_waiting(Outcome::kCharging, "waiting ended: " + why);
  // Not interruptible now: it finishes first (or on_interruptible_changed() comes back here).
  if (interruptible_now()) preempt_for(Outcome::kCharging, "preempted: " + why, {});
}

bool Executor::must_charge() {
  read_battery();
  if (!low_battery_) {
    if (!below_threshold()) return planned_charge_ && charging_as_planned();
    planned_charge_.reset();  // the hard threshold takes over
    enter_low_battery();  // found low between two tasks
    reschedule({}, "battery low");
    return true;
  }
  if (battery_->level() < resume_level()) return true;
  book_.note_robot("charged", Outcome::kCharging,
                   fmt::format("battery {} after {} since it fell below {}: dispatch resumes",
                               percent(battery_->level()), duration_text(clock_.now() - low_since_),
                               percent(options_.battery_threshold)));
  reschedule({}, "charged");  // still charging for it: what no longer fits is dropped for the charge
  low_battery_ = false;
  return false;
}

void Executor::charge() {
  if (robot_.location() != options_.dock) return go_to_dock();
  // On the charger: look again when the resume level is expected (at least every slot).
  look_again_at(clock_.now() + std::clamp(time_to_charge() + seconds(1), seconds(1), options_.slot_width));
}

}  // namespace rondo::exec
