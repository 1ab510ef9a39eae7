#include "charging.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "rondo/map/map_geometry.h"
#include "text.h"

namespace rondo::exec {
namespace {

constexpr int kWayHomeDoublings = 4;  // a closed way home is tried again after at most 2^4 slots

}  // namespace

std::string percent(double level) { return fmt::format("{:.1f} %", level * 100); }

Charging::Charging(ChargingContext ctx) : ctx_(ctx), watch_(ctx.map) {
  if (ctx_.options.battery_planning) metres_home_ = map::shortest_metres_to(ctx_.map, ctx_.options.dock);
}

void Charging::read() { watch_.read(ctx_.clock.now(), ctx_.robot.battery(), ctx_.robot.charging()); }

BatteryFigures Charging::figures() const {
  BatteryFigures f = watch_.figures();
  f.low_battery = low_count_;
  return f;
}

double Charging::resume_level() const {
  const ExecutorOptions& o = ctx_.options;
  return o.battery_resume > 0 ? o.battery_resume : o.battery_reserve;
}

bool Charging::below_threshold() const {
  if (watch_.level() < home_level()) return true;
  return ctx_.options.battery_threshold > 0 && watch_.level() < ctx_.options.battery_threshold;
}

double Charging::home_level() const {
  if (!ctx_.options.battery_planning) return 0;
  const double home_hours = way_home_hours();
  const BatteryPrediction p = way_home(home_hours);
  // Readings come between edges: one more edge away from the dock must still leave the way back.
  double next_edge = 0;
  for (const map::EdgeIndex e : ctx_.map.out_edges(ctx_.robot.location()))
    next_edge = std::max(next_edge, edge_cost(e));
  return ctx_.options.battery_reserve + p.mean + next_edge + margin_over(p, home_hours);
}

double Charging::margin_over(const BatteryPrediction& p, double hours) const {
  return ctx_.options.battery_margin *
         std::sqrt(p.standard_error * p.standard_error + drift_.variance_per_hour() * std::max(hours, 0.0));
}

double Charging::way_home_hours() const {
  const Duration d = ctx_.travel.travel(ctx_.robot.location(), ctx_.options.dock, ctx_.clock.now());
  return to_seconds(std::min<Duration>(d, hours(24))) / 3600.0;
}

BatteryPrediction Charging::way_home(double hours) const {
  const map::NodeIndex here = ctx_.robot.location();
  const double metres = here < metres_home_.size() && std::isfinite(metres_home_[here]) ? metres_home_[here] : 0;
  return watch_.estimator().predict({.metres = metres, .hours_moving = hours});
}

double Charging::edge_cost(map::EdgeIndex e) const {
  return watch_.estimator()
      .predict({.metres = map::edge_length(ctx_.map, e),
                .hours_moving = to_seconds(map::nominal_travel_time(ctx_.map, e)) / 3600.0})
      .mean;
}

Duration Charging::time_to_charge() const {
  const bool planned = planned_ && !low_;
  const double to = planned ? planned_->target : resume_level();
  const double hours = watch_.estimator().hours_to_charge(watch_.level(), to);
  Duration d = hours > 0 ? from_seconds(hours * 3600) : Duration{0};
  if (planned) d = std::clamp(planned_->until - ctx_.clock.now(), Duration{0}, d);
  return d;
}

double Charging::level_when_free(Time free, bool acting) const {
  if (low_) return resume_level();
  if (planned_) return std::max(planned_->target, watch_.level());
  double level = watch_.level();
  // The running task (and the on-demand ones before the plan) until then, counted as acting.
  if (acting) level -= watch_.estimator().predict({.hours_acting = to_seconds(free - ctx_.clock.now()) / 3600.0}).mean;
  return std::clamp(level, 0.0, 1.0);
}

std::optional<Charging::Short> Charging::short_for(const TaskId& id, map::NodeIndex from) const {
  const ExecutorOptions& o = ctx_.options;
  if (!o.battery_planning) return std::nullopt;
  const Task& task = ctx_.book.at(id).task;
  const map::NodeIndex start = task.start_node.empty() ? from : *ctx_.map.find_node(task.start_node);
  const map::NodeIndex end = task.end_node.empty() ? start : *ctx_.map.find_node(task.end_node);
  const auto finite = [](double m) { return std::isfinite(m) ? m : 0.0; };
  const auto hours_of = [](Duration d) { return to_seconds(std::min<Duration>(d, hours(24))) / 3600.0; };
  const Time now = ctx_.clock.now();
  const Duration there = ctx_.travel.travel(from, start, now);
  const Duration work = ctx_.book.at(id).remaining();
  const Duration back = ctx_.travel.travel(end, o.dock, now + std::min<Duration>(there, hours(24)) + work);
  const BatteryPrediction p = watch_.estimator().predict(
      {.metres = finite(map::shortest_metres(ctx_.map, from)[start]) +
                 (end < metres_home_.size() ? finite(metres_home_[end]) : 0),
       .hours_moving = hours_of(there) + hours_of(back),
       .hours_acting = hours_of(work)});
  const double hours = hours_of(there) + hours_of(work) + hours_of(back);
  const double left = watch_.level() - p.mean - drift_.per_hour() * hours;
  const double keep = o.battery_reserve + margin_over(p, hours);
  if (left >= keep) return std::nullopt;
  return Short{.needed = watch_.level() + (keep - left),
               .why = fmt::format("task {} would leave about {} after the way back to the charger, below the "
                                  "{} to keep",
                                  id, percent(std::max(left, 0.0)), percent(keep))};
}

void Charging::enter_low() {
  low_ = true;
  ++low_count_;
  low_since_ = ctx_.clock.now();
  const double home = home_level();
  const std::string below =
      watch_.level() < home
          ? fmt::format("below {}, what the way to the charger needs to keep the reserve {}", percent(home),
                        percent(ctx_.options.battery_reserve))
          : fmt::format("below the hard threshold {}", percent(ctx_.options.battery_threshold));
  ctx_.book.note_robot(ctx_.options.robot_name, EventKind::kBatteryLow, Outcome::kCharging,
                       fmt::format("battery {} at {}, {}: the robot goes to charge at the next interruptible moment "
                                   "and starts nothing new until {} (about {} on the charger)",
                                   percent(watch_.level()), ctx_.map.node(ctx_.robot.location()).name, below,
                                   percent(resume_level()), duration_text(time_to_charge())));
}

void Charging::start_planned(Time until, Duration length, double target) {
  const Time now = ctx_.clock.now();
  planned_ = PlannedCharge{.since = now, .until = until, .length = length, .target = std::max(target, resume_level())};
  ctx_.book.note_robot(ctx_.options.robot_name, EventKind::kCharging, Outcome::kCharging,
                       fmt::format("a planned charge: battery {} at {}, on the charger until {} or about {}",
                                   percent(watch_.level()), ctx_.map.node(ctx_.robot.location()).name,
                                   ctx_.zone.format_clock(until), percent(planned_->target)));
}

bool Charging::planned_goes_on() {
  PlannedCharge& c = *planned_;
  const Time now = ctx_.clock.now();
  if (!c.on_charger && ctx_.robot.location() == ctx_.options.dock) {
    // Reached the charger: it stays as long as planned, however long the way took.
    c.on_charger = true;
    c.until = std::max(c.until, now + c.length);
  }
  // The way to the charger takes longer than the charge itself: given up (the hard threshold stays).
  const bool missed = !c.on_charger && now >= c.until + c.length;
  if (watch_.level() < c.target && (c.on_charger ? now < c.until : !missed)) return true;
  if (missed)
    ctx_.book.note_robot(ctx_.options.robot_name, EventKind::kChargeMissed, Outcome::kCharging,
                         fmt::format("battery {}: the robot did not reach the charger in {} since {}: dispatch resumes",
                                     percent(watch_.level()), duration_text(now - c.since),
                                     ctx_.zone.format_clock(c.since)));
  else
    ctx_.book.note_robot(ctx_.options.robot_name, EventKind::kCharged, Outcome::kCharging,
                         fmt::format("battery {} after the planned charge ({} since {}): dispatch resumes",
                                     percent(watch_.level()), duration_text(now - c.since),
                                     ctx_.zone.format_clock(c.since)));
  planned_.reset();
  return false;
}

// The way to the charger found closed while the battery is planned: every attempt costs some of
// the battery it is meant to save, and a robot shut out overnight (a door locked after hours) would
// spend the night trying. So the next trip waits twice as long after each failed one (a slot, then
// 2, 4, 8 and at most 16 slots; at once the longest when the battery above what the way home needs
// would not pay for two more attempts), and at least until the first slot start at which the
// snapshot's model (what time of day and week say, without the live model's memory of the last
// failure) holds the edge likely passable, looked for up to three days ahead.
Time Charging::retry_way_home(map::EdgeIndex edge) {
  const ExecutorOptions& o = ctx_.options;
  const Time now = ctx_.clock.now();
  if (!way_home_closed_ || way_home_closed_->edge != edge) way_home_closed_ = WayHomeClosed{.edge = edge};
  WayHomeClosed& w = *way_home_closed_;
  ++w.failures;
  const double home_hours = way_home_hours();
  const BatteryPrediction home = way_home(home_hours);
  const double spare = watch_.level() - (o.battery_reserve + home.mean + margin_over(home, home_hours));
  const int doublings = spare < 2 * edge_cost(edge) ? kWayHomeDoublings : std::min(w.failures - 1, kWayHomeDoublings);
  Time at = now + o.slot_width * (1 << doublings);
  std::string learned;
  for (Time t = ctx_.travel.slot_start(now) + o.slot_width; t <= now + hours(72); t += o.slot_width) {
    const double p = ctx_.snapshot.outcome(edge, t).success_probability;
    if (p < kLikelyPassable) continue;
    if (t > at) {
      at = t;
      learned = fmt::format(", when it is likely passable again (p = {:.2f}, learned)", p);
    }
    break;
  }
  w.retry_at = at;
  ctx_.book.note_robot(ctx_.options.robot_name, EventKind::kWayHomeClosed, Outcome::kNoRouteNow,
                       fmt::format("battery {} at {}: {} failed on the way to the charger ({} in a row); the next try "
                                   "at {}{}",
                                   percent(watch_.level()), ctx_.map.node(ctx_.robot.location()).name,
                                   ctx_.map.edge(edge).id, w.failures, ctx_.zone.format_clock(at), learned));
  return at;
}

void Charging::crossed(const EdgeAttempt& a) {
  if (!way_home_closed_) return;
  if ((a.succeeded() && a.edge == way_home_closed_->edge) || ctx_.robot.location() == ctx_.options.dock)
    way_home_closed_.reset();
}

std::optional<Time> Charging::way_home_closed_until() const {
  if (!way_home_closed_) return std::nullopt;
  return way_home_closed_->retry_at;
}

}  // namespace rondo::exec
