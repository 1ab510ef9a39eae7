#include "charge_planning.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace rondo::exec {
namespace {

double in_hours(Duration d) { return to_seconds(d) / 3600.0; }

// The level as the robot goes: the last known level, and what it did since (the prediction's
// uncertainty grows with it). A charge that fills the battery makes the level known again.
class LevelTrack {
 public:
  LevelTrack(const ChargePlan& plan, const schedule::Problem& problem, double level)
      : plan_(plan), problem_(problem), base_(level), known_at_(problem.robot.time) {}

  Duration drive(schedule::LocationIndex from, schedule::LocationIndex to, Time depart) {
    const Duration d = problem_.travel->travel(from, to, depart);
    use_.metres += plan_.metres_between(from, to);
    use_.hours_moving += in_hours(d);
    return d;
  }
  void idle(Duration d) { use_.hours_idle += in_hours(std::max(d, Duration{0})); }
  void act(Duration d) { use_.hours_acting += in_hours(std::max(d, Duration{0})); }
  // `end`: when the charge ends (a full battery is known again from then on).
  void charge(Duration d, Time end) {
    use_.hours_charging += in_hours(std::max(d, Duration{0}));
    if (base_ - plan_.estimator.predict(use_).mean >= 1) base_ = 1, use_ = {}, known_at_ = end;
  }
  // At `at`: the model's prediction, less what plans have missed per hour since the level was known.
  double level(Time at) const {
    return base_ - plan_.estimator.predict(use_).mean - plan_.drift_per_hour * hours_since(at);
  }
  double floor(Time at) const {
    const double se = plan_.estimator.predict(use_).standard_error;
    return plan_.reserve + plan_.margin * std::sqrt(se * se + plan_.drift_variance_per_hour * hours_since(at));
  }

 private:
  const ChargePlan& plan_;
  const schedule::Problem& problem_;
  double base_;
  double hours_since(Time at) const { return std::max(0.0, in_hours(at - known_at_)); }

  BatteryUse use_{};
  Time known_at_;
};

// Records a checked point in the profile.
// `home`: what the way to the dock from there is predicted to take (the level must keep it).
void check(LevelProfile& out, const LevelTrack& track, std::size_t position, Time at, double home = 0) {
  const double level = track.level(at);
  const double floor = track.floor(at) + home;
  out.points.emplace_back(at, level);
  out.lowest = std::min(out.lowest, level);
  if (level >= floor) {
    if (out.short_at) out.deficit = std::max(out.deficit, floor - level);
    return;
  }
  if (!out.short_at) {
    out.short_at = position;
    out.short_level = level;
    out.short_floor = floor;
    out.short_time = at;
  }
  out.deficit = std::max(out.deficit, floor - level);
}

std::string percent(double level) { return fmt::format("{:.0f} %", level * 100); }

}  // namespace

double ChargePlan::metres_between(schedule::LocationIndex from, schedule::LocationIndex to) const {
  const std::size_t n = static_cast<std::size_t>(std::llround(std::sqrt(static_cast<double>(metres.size()))));
  if (from >= n || to >= n) return 0;
  const double m = metres[from * n + to];
  return std::isfinite(m) ? m : 0;
}

LevelProfile predict_levels(const schedule::Problem& problem, const schedule::Schedule& schedule,
                            const ChargePlan& plan, std::size_t first_charge) {
  LevelProfile out;
  LevelTrack track(plan, problem, plan.level);
  out.lowest = plan.level;
  out.points.emplace_back(problem.robot.time, plan.level);
  schedule::LocationIndex here = problem.robot.location;
  for (std::size_t pos = 0; pos < schedule.entries.size(); ++pos) {
    const schedule::ScheduledTask& e = schedule.entries[pos];
    const schedule::ProblemTask& t = problem.tasks[e.task];
    const bool is_charge = e.task >= first_charge;
    if (here == plan.dock) {  // standing on the charger until it leaves
      track.charge(e.waiting, e.start - e.travel);
      track.drive(here, t.start_location, e.start - e.travel);
    } else if (e.waiting > plan.dock_when_waiting_over && !is_charge) {
      // The executor spends a long wait on the charger (Dispatcher::next): there and back.
      const Duration to_dock = track.drive(here, plan.dock, e.depart);
      const Duration back = problem.travel->travel(plan.dock, t.start_location, e.start - e.travel);
      track.charge(e.start - back - (e.depart + to_dock), e.start - back);
      track.drive(plan.dock, t.start_location, e.start - back);
    } else {
      track.drive(here, t.start_location, e.depart);
      track.idle(e.waiting);
    }
    if (is_charge) {
      check(out, track, pos, e.arrival);
      track.charge(t.duration, e.end);
    } else {
      track.act(t.duration);
      const Duration home = problem.travel->travel(t.end_location, plan.dock, e.end);
      check(out, track, pos, e.end,
            plan.estimator.predict({.metres = plan.metres_between(t.end_location, plan.dock),
                                    .hours_moving = in_hours(std::min<Duration>(home, hours(24)))})
                .mean);
    }
    out.after.push_back(track.level(e.end));
    here = t.end_location;
  }
  if (here != plan.dock) {
    const Time last = schedule.entries.empty() ? problem.robot.time : schedule.entries.back().end;
    const Duration home = track.drive(here, plan.dock, last);
    check(out, track, schedule.entries.size(), last + home);
  }
  return out;
}

void PlanDrift::observe(Time now, double level) {
  if (plan_.size() < 2 || now > plan_.back().first) return;
  const double h = in_hours(now - plan_.front().first);
  if (h < 5.0 / 60) return;
  const auto after = std::lower_bound(plan_.begin(), plan_.end(), now,
                                      [](const std::pair<Time, double>& p, Time t) { return p.first < t; });
  double predicted = after->second;
  if (after != plan_.begin() && after->first > now) {
    const auto& [t0, l0] = *(after - 1);
    const double span = to_seconds(after->first - t0);
    predicted = span > 0 ? l0 + (after->second - l0) * to_seconds(now - t0) / span : l0;
  }
  const double e = std::clamp(predicted, 0.0, 1.0) - level;
  ++n_;
  hours_ += h;
  error_ += e;
  error_sq_ += e * e / h;
  plan_.clear();  // one observation per plan
}

double PlanDrift::per_hour() const { return std::max(0.0, error_ / (hours_ + 1.0)); }

double PlanDrift::variance_per_hour() const {
  constexpr double kPriorVariance = 0.05 * 0.05;
  constexpr double kPriorWeight = 2;
  const double b = error_ / (hours_ + 1.0);
  // Σ (e − b·h)² / h = Σ e²/h − 2b Σ e + b² Σ h
  const double ss = std::max(0.0, error_sq_ - 2 * b * error_ + b * b * hours_);
  return (ss + kPriorWeight * kPriorVariance) / (static_cast<double>(n_) + kPriorWeight);
}

namespace {

// Adds a charge before the task at `position` (or makes the charge already before it longer), so
// that the next solve can place it. False when no charge can go there.
bool charge_before(schedule::TryScheduleRequest& request, const PlannedAnswer& out, const LevelProfile& profile,
                   const ChargePlan& plan, int priority, int k) {
  schedule::Problem& problem = request.problem;
  const auto& entries = out.result.schedule.entries;
  const double rate = plan.estimator.rates().charging_per_hour;
  if (entries.empty() || !(rate > 0)) return false;  // only the way home falls short: nothing to move
  // The charge goes before the task that falls short (before the last one, for the way home).
  const std::size_t successor = entries[std::min(*profile.short_at, entries.size() - 1)].task;
  if (successor >= out.first_charge) return false;  // the way to a charge itself falls short
  // Enough for the rest of the schedule with a little to spare, never more than the reserve to full.
  const Duration longest = from_seconds((1.0 - plan.reserve) / rate * 3600.0);
  const double amount = std::min(profile.deficit + 0.05, 1.0 - plan.reserve);
  const Duration length = std::max<Duration>(minutes(10), from_seconds(amount / rate * 3600.0));
  std::vector<std::size_t>& after = problem.tasks[successor].after;
  const auto earlier = std::find_if(after.begin(), after.end(), [&](std::size_t a) { return a >= out.first_charge; });
  if (earlier != after.end()) {  // too short: made longer
    schedule::ProblemTask& c = problem.tasks[*earlier];
    c.duration = std::min<Duration>(c.duration + length, longest);
    c.deadline = c.release + hours(48) + c.duration;
    return true;
  }
  const std::size_t index = problem.tasks.size();
  problem.tasks.push_back({.id = fmt::format("charge-{}", k + 1),
                           .release = problem.robot.time,
                           .deadline = problem.robot.time + hours(48) + length,
                           .duration = length,
                           .priority = priority,
                           .start_location = plan.dock,
                           .end_location = plan.dock});
  problem.tasks[successor].after.push_back(index);
  request.new_tasks.push_back(index);
  request.cannot_preempt.push_back(index);
  return true;
}

// Refused: what comes from the first shortfall on is dropped for the battery. The tasks refused.
std::set<std::size_t> refuse_tail(schedule::TryScheduleRequest& request, PlannedAnswer& out,
                                  const LevelProfile& profile, const ChargePlan& plan) {
  schedule::Schedule& s = out.result.schedule;
  std::set<std::size_t> refused;
  const std::size_t from = std::min(*profile.short_at, s.entries.size() - 1);
  const std::string why =
      fmt::format("the battery would fall to {} by {}, below the {} it must keep there (the reserve {}, the way to "
                  "the charger and a margin), and no charge fits before it",
                  percent(std::max(profile.short_level, 0.0)), request.zone.format_clock(profile.short_time),
                  percent(profile.short_floor), percent(plan.reserve));
  for (std::size_t pos = from; pos < s.entries.size(); ++pos) {
    const std::size_t task = s.entries[pos].task;
    if (task >= out.first_charge)
      s.dropped.push_back({.task = task, .reason = "refused with the tasks after it"});
    else if (refused.insert(task).second)
      s.dropped.push_back({.task = task, .reason = why, .cause = schedule::DropCause::kDoesNotFit});
  }
  s.entries.resize(from);
  s.objective = Duration{0};
  for (const schedule::ScheduledTask& e : s.entries) s.objective += e.end - request.problem.robot.time;
  s.lower_bound.reset();  // of the whole problem, not of this prefix
  out.refused = true;
  return refused;
}

}  // namespace

PlannedAnswer plan_charges(schedule::TryScheduleRequest& request, const ChargePlan* plan,
                           const std::function<schedule::TryScheduleResult(schedule::TryScheduleRequest&)>& solve) {
  schedule::Problem& problem = request.problem;
  PlannedAnswer out{.result = solve(request), .first_charge = problem.tasks.size()};
  if (!plan || out.result.outcome == schedule::TryScheduleOutcome::kPreemptRunning) return out;
  std::set<std::size_t> dropped_without;
  for (const schedule::DroppedTask& d : out.result.schedule.dropped) dropped_without.insert(d.task);
  int top = std::numeric_limits<int>::min();
  for (const schedule::ProblemTask& t : problem.tasks) top = std::max(top, t.priority);
  const int charge_priority = top == std::numeric_limits<int>::max() ? top : std::max(top + 1, 1);

  LevelProfile profile = predict_levels(problem, out.result.schedule, *plan, out.first_charge);
  for (int k = 0; profile.short_at && k < plan->max_charges; ++k) {
    if (!charge_before(request, out, profile, *plan, charge_priority, k)) break;
    out.result = solve(request);
    if (out.result.outcome == schedule::TryScheduleOutcome::kPreemptRunning) return out;
    profile = predict_levels(problem, out.result.schedule, *plan, out.first_charge);
  }
  std::set<std::size_t> refused;
  if (profile.short_at && !out.result.schedule.entries.empty()) {
    refused = refuse_tail(request, out, profile, *plan);
    profile = predict_levels(problem, out.result.schedule, *plan, out.first_charge);
  }
  out.levels = profile.after;
  out.points = profile.points;
  for (const schedule::DroppedTask& d : out.result.schedule.dropped)
    if (d.task < out.first_charge && (refused.contains(d.task) || !dropped_without.contains(d.task)))
      out.for_battery.push_back(d.task);
  return out;
}

}  // namespace rondo::exec
