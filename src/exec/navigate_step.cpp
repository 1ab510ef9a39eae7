#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "found_blocked.h"
#include "rondo/exec/map_travel.h"
#include "rondo/plan/travel_planner.h"
#include "steps.h"
#include "text.h"
#include "traffic_link.h"

namespace rondo::exec {

// How long a journey waits for its way, held by other robots, before it overruns (unless its
// monitor had more left): the monitor does not count a wait, but a wait is not endless.
inline constexpr Duration kTrafficPatience = minutes(10);

NavigateStep::NavigateStep(StepContext& ctx, StepHooks hooks, Purpose purpose, std::optional<TaskId> task,
                           map::NodeIndex target)
    : RobotStep(ctx, std::move(hooks)), purpose_(purpose), task_(std::move(task)), target_(target) {}

void NavigateStep::start() {
  const Time now = ctx_.clock.now();
  const map::NodeIndex here = ctx_.robot.location();
  started_ = now;
  expected_ = ctx_.own(ctx_.travel.travel(here, target_, now));
  if (purpose_ == Purpose::kToStart) offline_expected_ = ctx_.own(ctx_.offline_travel.travel(here, target_, now));
  if (purpose_ != Purpose::kToStart && here == target_) return finish({.status = StepEnd::Status::kDone});
  const std::string& to = ctx_.map.node(target_).name;
  const std::string& from = ctx_.map.node(here).name;
  if (expected_ >= kUnreachable) {
    return finish({.status = StepEnd::Status::kFailed,
                   .outcome = Outcome::kNoRoute,
                   .reason = fmt::format("no route: from {} to {} at {}", from, to, ctx_.clock_text(now))});
  }
  if (purpose_ != Purpose::kToEnd) {
    if (std::optional<StepEnd> wait = leave_later(here, now)) return finish(std::move(*wait));
  }
  if (task_) {
    ctx_.book.transition(*task_, TaskState::kNavigating, Outcome::kDeparted,
                         fmt::format("to {}{} from {}, expected travel {}", to,
                                     purpose_ == Purpose::kToEnd ? " (its end place)" : "", from,
                                     duration_text(expected_)));
  } else {
    ctx_.book.note_robot(ctx_.options.robot_name, EventKind::kDeparted, Outcome::kDeparted,
                         fmt::format("to {} ({}) from {}, expected travel {}", to, errand(), from,
                                     duration_text(expected_)));
  }
  const ExecutorOptions& o = ctx_.options;
  Monitor::Limit limit = Monitor::limit("navigation overrun: still travelling", "the expected travel time", expected_,
                                        o.navigation_overrun, o.navigation_slack);
  if (o.risk_alpha) {
    // Under the chance constraint the schedule left this journey its (1 − α)-quantile before the
    // task's latest start: a journey within the learned spread of travel times is not a fault, and
    // is stopped only past the (1 − navigation_alpha)-quantile.
    const double level = 1.0 - o.navigation_alpha.value_or(*o.risk_alpha);
    const Duration q = ctx_.own(ctx_.travel.quantile_travel(here, target_, now, level));
    if (q < kUnreachable && q + o.navigation_slack > limit.after)
      limit = {.after = q + o.navigation_slack,
               .reason = fmt::format("navigation overrun: still travelling after {}, the limit is the {:g} "
                                     "quantile of the travel time {} + {}",
                                     duration_text(q + o.navigation_slack), level, duration_text(q),
                                     duration_text(o.navigation_slack))};
  }
  monitor_.arm(std::move(limit), [this](const std::string& why) { overran(why); });
  if (ctx_.in_fault) monitor_.suspend();
  advance();
}

const char* NavigateStep::errand() const {
  switch (purpose_) {
    case Purpose::kDock: return "idle: back to the dock";
    case Purpose::kOutOfService: return "out of service: to the dock";
    case Purpose::kCharge: return "to charge";
    case Purpose::kMakeWay:
      return "making way";
    case Purpose::kToStart:
    case Purpose::kToEnd: break;
  }
  return "a task's journey";
}

NavigateStep::~NavigateStep() {
  if (ctx_.traffic) ctx_.traffic->forget(this);
}

void NavigateStep::finish(StepEnd e) {
  release_way();
  end(std::move(e));
}

void NavigateStep::release_way() {
  if (!ctx_.traffic || ctx_.robot.busy()) return;
  if (waiting_for_way_) way_wait_ended("stopped");
  ctx_.traffic->stop(this, ctx_.robot.location());
}

int NavigateStep::rank() const {
  return task_ ? ctx_.book.at(*task_).task.priority : 0;
}

void NavigateStep::wait_for_way(map::NodeIndex here) {
  edge_.reset();  // nothing is driven while it waits: no attempt to watch
  if (!waiting_for_way_) {
    waiting_for_way_ = true;
    const Time now = ctx_.clock.now();
    ctx_.traffic->wait_began(here, now);
    const std::string text =
        fmt::format("at {}, its way held by {}", ctx_.map.node(here).name, ctx_.traffic->behind_text());
    if (const std::optional<Time> deadline = monitor_.deadline()) {
      before_wait_ = Monitor::Limit{.after = *deadline - now, .reason = monitor_.reason()};
      const Duration patience = std::max(before_wait_->after, kTrafficPatience);
      monitor_.extend({.after = patience,
                       .reason = fmt::format("navigation overrun: waited {} {}", duration_text(patience), text)});
    }
    note(EventKind::kTrafficWait, task_ ? text : fmt::format("{} ({})", text, errand()));
  }
  ctx_.traffic->when_waiting(
      this,
      [this] {
        if (waiting_for_way_ && !halting() && !ended()) advance();
      },
      [this](const traffic::MakeWay& m) { make_way(m); });
}

void NavigateStep::make_way(const traffic::MakeWay& m) {
  if (!waiting_for_way_ || halting() || ended() || ctx_.robot.busy() || ctx_.in_fault) {
    ctx_.traffic->stop(this, ctx_.robot.location());
    return;
  }
  way_wait_ended("made way");
  note(EventKind::kMadeWay,
       fmt::format("to {} ({}), making way for {}", ctx_.map.node(ctx_.map.to_index(m.route.back())).name,
                   traffic::to_string(m.why), ctx_.traffic->names(m.for_robots)));
  drive(Route{.edges = m.route, .committed = m.route.size()});
}

// The wait for the way ended: the monitor has again what it had left when the wait began.
void NavigateStep::way_wait_ended(const char* how) {
  waiting_for_way_ = false;
  ctx_.traffic->wait_ended(ctx_.clock.now(), how);
  if (before_wait_ && monitor_.deadline()) monitor_.extend(*before_wait_);
  before_wait_.reset();
}

// A task's journey writes its task's events, an own journey the robot's.
void NavigateStep::note(EventKind kind, const std::string& text) {
  if (task_)
    ctx_.book.note(*task_, kind, Outcome::kNone, text);
  else
    ctx_.book.note_robot(ctx_.options.robot_name, kind, Outcome::kNone, text);
}

void NavigateStep::drive(Route route) {
  edge_ = route.edges.front();
  edge_since_ = ctx_.clock.now();
  edge_p_ = std::clamp(ctx_.models.outcome(*edge_, edge_since_).success_probability, 0.0, 1.0);
  ctx_.before_command();
  ctx_.robot.drive(route);
}

StepEnd NavigateStep::halted_end() {
  release_way();
  if (gave_up_) return *gave_up_;
  return {.status = StepEnd::Status::kHalted};
}

void NavigateStep::advance() {
  const map::NodeIndex here = ctx_.robot.location();
  if (here == target_) return arrived();
  if (ctx_.in_fault) return;  // resume() goes on from where the robot is
  if (failed_edges_ >= ctx_.options.max_failed_edges) {
    return finish({.status = StepEnd::Status::kFailed,
                   .outcome = Outcome::kNavigationGaveUp,
                   .reason = fmt::format("navigation gave up: {} failed edge attempts near {}", failed_edges_,
                                         ctx_.map.node(here).name)});
  }
  if (!ctx_.planner.policy(target_, ctx_.clock.now()).next_edge(here)) {
    return finish({.status = StepEnd::Status::kFailed,
                   .outcome = Outcome::kNoRoute,
                   .reason = fmt::format("no route: from {} to {} at {}", ctx_.map.node(here).name,
                                         ctx_.map.node(target_).name, ctx_.clock_text(ctx_.clock.now()))});
  }
  // The next edge is committed; the rest of the policy's expected route is the horizon. With the
  // traffic manager, what it grants is committed (a VDA 5050 order's base), and nothing granted is
  // a wait.
  std::vector<map::EdgeIndex> route = expected_route(here);
  std::size_t committed = 1;
  if (ctx_.traffic) {
    committed = ctx_.traffic->request(this, here, route, rank());
    if (committed == 0) return wait_for_way(here);
    if (waiting_for_way_) way_wait_ended("passed");
  }
  drive(Route{.edges = std::move(route), .committed = committed});
}

void NavigateStep::overran(const std::string& why) {
  if (!task_) {  // an own journey: stopped where it is; the executor decides what comes next
    gave_up_ = StepEnd{.status = StepEnd::Status::kFailed, .outcome = Outcome::kNavigationOverrun, .reason = why};
    return halt();
  }
  const Time now = ctx_.clock.now();
  // Fired only to see whether the attempt in progress hangs (watch_until): nothing else is decided.
  const bool hang_check = std::exchange(hang_check_, false);
  const std::optional<Time> until = window_open_until();
  if (!until) {
    return hooks_.overrun(Outcome::kNavigationOverrun,
                          hang_check ? fmt::format("navigation overrun: still travelling at {}, after {}; the task "
                                                   "can no longer be expected to start in its window",
                                                   ctx_.clock_text(now), duration_text(now - started_))
                                     : why);
  }
  if (const std::optional<Time> hangs = hangs_at(); hangs && now >= *hangs) {
    return hooks_.overrun(Outcome::kNavigationOverrun,
                          fmt::format("navigation overrun: an attempt of {} still running after {}, past {:g} x the "
                                      "longest of its learned attempt times + {}: taken to hang",
                                      ctx_.map.edge(*edge_).id, duration_text(now - edge_since_), kHangFactor,
                                      duration_text(ctx_.options.navigation_slack)));
  }
  if (!hang_check) {
    if (const std::optional<double> chance = success_chance(now); chance && *chance < 0.5) {
      return hooks_.overrun(Outcome::kNavigationOverrun,
                            fmt::format("{}; an attempt of {} still running after {} is more likely to fail, by its "
                                        "learned attempt times",
                                        why, ctx_.map.edge(*edge_).id, duration_text(now - edge_since_)));
    }
    if (!window_watch_)
      ctx_.book.note(*task_, EventKind::kOverrun, Outcome::kWindowStillOpen,
                     fmt::format("{}; the task can still start in its window, so the journey goes on until {}", why,
                                 ctx_.clock_text(*until)));
    window_watch_ = true;
  }
  watch_until(*until);
}

void NavigateStep::watch_until(Time until) {
  const Time now = ctx_.clock.now();
  if (const std::optional<Time> hangs = hangs_at(); hangs && *hangs < until) {
    hang_check_ = true;
    monitor_.extend({.after = *hangs - now, .reason = "navigation overrun: the attempt in progress may hang"});
    return;
  }
  monitor_.extend({.after = until - now,
                   .reason = fmt::format("navigation overrun: still travelling at {}, after {}; the task can no "
                                         "longer be expected to start in its window",
                                         ctx_.clock_text(until), duration_text(until - started_))});
}

// A hung navigation (the vehicle stuck, no progress, no failure reported) would otherwise run on to
// the window's end, since past every learned attempt success_chance() says nothing. The longest
// learned attempt is a group mean of the tail, so the factor is wide: no successful attempt of the
// validation runs ran past it.
std::optional<Time> NavigateStep::hangs_at() const {
  if (!edge_) return std::nullopt;
  const plan::EdgeCrossing o = ctx_.models.outcome(*edge_, edge_since_);
  plan::RouteLeg leg{.success_probability = std::clamp(o.success_probability, 0.0, 1.0),
                     .attempt_seconds = o.expected_seconds};
  ctx_.models.attempt_laws(*edge_, edge_since_, leg);
  if (leg.success_law.empty() && leg.failure_law.empty()) return std::nullopt;
  double longest = 0.0;
  for (const std::vector<plan::DurationPoint>* law : {&leg.success_law, &leg.failure_law})
    for (const plan::DurationPoint& d : *law) longest = std::max(longest, d.seconds);
  if (!(longest > 0.0) || !std::isfinite(longest)) return std::nullopt;
  return edge_since_ + from_seconds(kHangFactor * longest) + ctx_.options.navigation_slack;
}

std::optional<double> NavigateStep::success_chance(Time now) const {
  if (!edge_) return std::nullopt;
  const plan::EdgeCrossing o = ctx_.models.outcome(*edge_, edge_since_);
  plan::RouteLeg leg{.success_probability = std::clamp(o.success_probability, 0.0, 1.0),
                     .attempt_seconds = o.expected_seconds};
  ctx_.models.attempt_laws(*edge_, edge_since_, leg);
  if (leg.success_law.empty() || leg.failure_law.empty()) return std::nullopt;
  const double elapsed = to_seconds(now - edge_since_);
  const auto longer = [elapsed](const std::vector<plan::DurationPoint>& law) {
    double total = 0.0, beyond = 0.0;
    for (const plan::DurationPoint& d : law) {
      total += d.weight;
      if (d.seconds > elapsed) beyond += d.weight;
    }
    return total > 0.0 ? beyond / total : 0.0;
  };
  const double succeeding = leg.success_probability * longer(leg.success_law);
  const double failing = (1.0 - leg.success_probability) * longer(leg.failure_law);
  // Past every learned attempt the laws say nothing (their points are group means, and a tail
  // runs past its mean): the window decides. Choosing by the longer law's last point instead
  // stopped Witham's journeys as before the watch (validation seeds 101-110: late + overrun
  // 0.86-1.01 of expected values' against 0.55-0.62).
  if (!(succeeding + failing > 0.0)) return std::nullopt;
  return succeeding / (succeeding + failing);
}

std::optional<Time> NavigateStep::window_open_until() const {
  const ExecutorOptions& o = ctx_.options;
  if (purpose_ != Purpose::kToStart || !o.risk_alpha || !o.navigation_window || !edge_) return std::nullopt;
  const Time now = ctx_.clock.now();
  const map::NodeIndex heading = ctx_.map.to_index(*edge_);
  Duration rest{0};
  if (heading != target_) {
    rest = ctx_.own(ctx_.travel.quantile_travel(heading, target_, now, 1.0 - *o.risk_alpha));
    if (rest >= kUnreachable) return std::nullopt;
  }
  const Time until = ctx_.book.at(*task_).latest_start(o.on_demand_patience) - rest;
  if (until < now + seconds(1)) return std::nullopt;
  return until;
}

// The edges the policy expects to take from `from` to the target if every attempt succeeds (the
// first is the policy's next edge), cut where it would loop.
std::vector<map::EdgeIndex> NavigateStep::expected_route(map::NodeIndex from) const {
  const plan::Policy& policy = ctx_.planner.policy(target_, ctx_.clock.now());
  std::vector<map::EdgeIndex> route;
  std::vector<bool> seen(ctx_.map.node_count(), false);
  map::NodeIndex at = from;
  while (at != target_ && !seen[at] && route.size() < ctx_.map.node_count()) {
    seen[at] = true;
    const std::optional<map::EdgeIndex> e = policy.next_edge(at);
    if (!e) break;
    route.push_back(*e);
    at = ctx_.map.to_index(*e);
  }
  return route;
}

void NavigateStep::arrived() {
  monitor_.cancel();
  // The report's travel-estimate errors (rondo run); a service that forgets finished tasks keeps
  // none of their navigations either.
  if (purpose_ == Purpose::kToStart && !ctx_.options.forget_finished)
    ctx_.navigations.push_back({.task = *task_, .start = started_, .expected = expected_,
                                .offline_expected = offline_expected_, .actual = ctx_.clock.now() - started_,
                                .arrived = true});
  if (!task_)
    ctx_.book.note_robot(ctx_.options.robot_name, EventKind::kArrived, Outcome::kArrived,
                         fmt::format("at {} ({}) after {}, expected {}", ctx_.map.node(target_).name, errand(),
                                     duration_text(ctx_.clock.now() - started_), duration_text(expected_)));
  finish({.status = StepEnd::Status::kDone});
}

void NavigateStep::on_edge_finished(const EdgeAttempt& a) {
  if (ctx_.traffic) {
    if (a.outcome == EdgeOutcome::kSucceeded) {
      ctx_.traffic->crossed(a.edge);
    } else if (!ctx_.robot.busy()) {
      ctx_.traffic->stop(this, ctx_.robot.location());  // back at its node (or where it stopped)
    }
  }
  // What every journey knows of the edge (FoundBlocked): a run of failures, whichever journey made it.
  if (a.outcome == EdgeOutcome::kSucceeded) ctx_.found_blocked.passed(a.edge);
  if (a.outcome == EdgeOutcome::kFailed)
    ctx_.found_blocked.failed(a.edge, edge_ == a.edge ? edge_p_ : 0.0, ctx_.clock.now());  // 0: no surprise
  if (a.outcome == EdgeOutcome::kCancelled) return finish(halted_end());
  if (ctx_.robot.busy()) return;  // more of a committed route to come
  if (halting()) return finish(halted_end());
  if (a.outcome == EdgeOutcome::kFailed) {
    ++failed_edges_;
    if (purpose_ != Purpose::kToEnd && ctx_.options.blocked_edge != ExecutorOptions::BlockedEdge::kRetry) {
      if (std::optional<std::string> why = not_worth_trying(a)) {
        const bool wait = ctx_.options.blocked_edge == ExecutorOptions::BlockedEdge::kWait;
        // Found blocked: every journey holds it so until the live model holds it likely passable.
        const Time now = ctx_.clock.now();
        if (const auto open = passable_again(ctx_.models, ctx_.planner, ctx_.options.slot_width, a.edge, now,
                                             now + hours(24)))
          ctx_.found_blocked.hold(a.edge, open->first);
        monitor_.cancel();
        return finish({.status = wait ? StepEnd::Status::kBlocked : StepEnd::Status::kFailed,
                       .outcome = Outcome::kNoRouteNow,
                       .reason = std::move(*why),
                       .edge = a.edge});
      }
    }
    // A trip to the charger when the battery matters: an edge more likely than not to fail again is
    // not tried again and again on the battery it is going to save; the executor looks again later.
    if (!task_ && ctx_.options.battery_planning &&
        ctx_.models.outcome(a.edge, ctx_.clock.now()).success_probability < 0.5) {
      monitor_.cancel();
      return finish({.status = StepEnd::Status::kFailed,
                     .outcome = Outcome::kNoRouteNow,
                     .reason = fmt::format("no route to the charger now: {} failed and is more likely than not to fail "
                                           "again",
                                           ctx_.map.edge(a.edge).id),
                     .edge = a.edge});
    }
  }
  advance();
}

// The travel estimate of a departure now prices every retry of a blocked edge at the p it has now,
// while the live model's p recovers with the time since the failure: leaving at a later slot start
// may arrive sooner. The slot starts up to the task's latest start (at most a day ahead) are read.
std::optional<StepEnd> NavigateStep::leave_later(map::NodeIndex here, Time now) const {
  if (ctx_.options.blocked_edge != ExecutorOptions::BlockedEdge::kWait) return std::nullopt;
  const Time day = now + hours(24);
  const Time latest = task_ ? std::min(ctx_.book.at(*task_).latest_start(ctx_.options.on_demand_patience), day) : day;
  const std::vector<map::EdgeIndex> route = expected_route(here);
  std::optional<map::EdgeIndex> blocked;
  double p = 1;
  for (map::EdgeIndex e : route) {
    p = ctx_.models.outcome(e, now).success_probability;
    if (p < kLikelyPassable) {
      blocked = e;
      break;
    }
  }
  if (blocked) {
    Time leave = now;
    Time arrive = now + expected_;
    for (Time t = ctx_.travel.slot_start(now) + ctx_.options.slot_width; t <= latest; t += ctx_.options.slot_width) {
      const Duration d = ctx_.own(ctx_.travel.at_slot(here, target_, t));
      if (d < kUnreachable && t + d < arrive) {
        leave = t;
        arrive = t + d;
      }
    }
    if (leave != now)
      return StepEnd{.status = StepEnd::Status::kBlocked,
                     .outcome = Outcome::kNoRouteNow,
                     .reason = fmt::format("no route now: the way to {} crosses {}, held to be blocked (p = {:.2f}); "
                                           "leaving at {} is expected to arrive at {}, sooner than leaving now ({})",
                                           ctx_.map.node(target_).name, ctx_.map.edge(*blocked).id, p,
                                           ctx_.clock_text(leave), ctx_.clock_text(arrive),
                                           ctx_.clock_text(now + expected_)),
                     .edge = blocked,
                     .not_before = leave};
  }
  // An edge a journey found blocked (FoundBlocked): held so until it is likely passable again, when
  // this journey can wait that long (else it goes now, and may find it open).
  for (map::EdgeIndex e : route) {
    const std::optional<Time> held = ctx_.found_blocked.held_until(e, now);
    if (!held || *held > latest) continue;
    const FoundBlocked::Run run = ctx_.found_blocked.run(e, now);
    return StepEnd{.status = StepEnd::Status::kBlocked,
                   .outcome = Outcome::kNoRouteNow,
                   .reason = fmt::format("no route now: the way to {} crosses {}, found blocked at {} ({} failed "
                                         "attempts in a row); held so until {}, when it is likely passable again",
                                         ctx_.map.node(target_).name, ctx_.map.edge(e).id, ctx_.clock_text(run.last),
                                         run.failures, ctx_.clock_text(*held)),
                   .edge = e,
                   .not_before = *held};
  }
  return std::nullopt;
}

std::optional<std::string> NavigateStep::not_worth_trying(const EdgeAttempt& failed) const {
  const std::optional<Time> limit = monitor_.deadline();
  if (!limit) return std::nullopt;  // held by a fault: the monitor decides later
  const Time now = ctx_.clock.now();
  const map::NodeIndex here = ctx_.robot.location();
  if (here == target_) return std::nullopt;
  const Duration left = ctx_.own(ctx_.travel.travel(here, target_, now));
  if (left >= kUnreachable) return std::nullopt;  // no way at all from here: advance() says so
  const map::Edge& e = ctx_.map.edge(failed.edge);
  // A run of failures (by this journey and those before it) that the live model gave less than
  // kRefuted of a chance says the model has not learned this closure yet, and the robot need not
  // learn it by hammering. An own journey has no window to meet; a task's journey stops only when
  // its task can wait until the edge is likely passable again (else it tries on: a burst of
  // failures often clears).
  if (const FoundBlocked::Run run = ctx_.found_blocked.run(failed.edge, now);
      run.refuted() &&
      (!task_ || passable_again(ctx_.models, ctx_.planner, ctx_.options.slot_width, failed.edge, now,
                                ctx_.book.at(*task_).latest_start(ctx_.options.on_demand_patience))))
    return fmt::format("no route now: {} failed {} times in a row, a run the live model gave a chance of {:.2g}",
                       e.id, run.failures, run.chance);
  const int tries = ctx_.options.max_failed_edges - failed_edges_;
  const double p = std::clamp(ctx_.models.outcome(failed.edge, now).success_probability, 0.0, 1.0);
  if (tries > 0 && std::pow(1 - p, tries) > 0.5)
    return fmt::format("no route now: {} failed, and the next {} attempts are more likely than not to fail too "
                       "(p = {:.3f} each)",
                       e.id, tries, p);
  if (now + left <= *limit) return std::nullopt;
  return fmt::format(
      "no route now: {} failed; the way from {} to {} is expected to take {} more, past the "
      "navigation's limit at {}",
      e.id, ctx_.map.node(here).name, ctx_.map.node(target_).name,
      duration_text(left), ctx_.clock_text(*limit));
}

}  // namespace rondo::exec
