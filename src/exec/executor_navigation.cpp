// The executor navigating: following the MDP policy edge by edge to a task's start or the dock,
// re-planning after every edge, logging every attempt to the traversal log.
#include <fmt/format.h>

#include "rondo/exec/executor.h"
#include "rondo/store/traversal_log.h"

namespace rondo::exec {

void Executor::begin_navigation(map::NodeIndex target, Duration expected) {
  phase_ = current_ ? Phase::kNavigating : Phase::kDocking;
  nav_target_ = target;
  nav_start_ = clock_.now();
  nav_expected_ = expected;
  nav_offline_expected_ = current_ ? offline_estimate(robot_.location(), target) : expected;
  failed_edges_ = 0;
  if (current_) {
    nav_monitor_ = arm_monitor(CancelIntent::kNavigationOverrun, "navigation overrun: still travelling",
                               "the expected travel time", expected, options_.navigation_overrun,
                               options_.navigation_slack);
  }
  step_navigation();
}

void Executor::step_navigation() {
  const map::NodeIndex here = robot_.location();
  if (here == nav_target_) {
    arrived();
    return;
  }
  if (fault_) return;  // on_ready() goes on from where the robot is
  if (failed_edges_ >= options_.max_failed_edges) {
    return abandon_navigation(Outcome::kNavigationGaveUp, fmt::format("navigation gave up: {} failed edge attempts near {}", failed_edges_,
                                          map_.node(here).name));
  }
  const plan::Policy& policy = planner_->policy(nav_target_, clock_.now());
  const std::optional<map::EdgeIndex> edge = policy.next_edge(here);
  if (!edge) {
    return abandon_navigation(Outcome::kNoRoute, fmt::format("no route: from {} to {} at {}", map_.node(here).name,
                                                             map_.node(nav_target_).name, fmt_time(clock_.now())));
  }
  // The next edge is committed; the rest of the policy's expected route is the horizon.
  robot_.drive(Route{.edges = expected_route(policy, here), .committed = 1});
}

// The edges the policy expects to take from `from` to the target if every attempt succeeds (the
// first is the policy's next edge), cut where it would loop.
std::vector<map::EdgeIndex> Executor::expected_route(const plan::Policy& policy, map::NodeIndex from) const {
  std::vector<map::EdgeIndex> route;
  std::vector<bool> seen(map_.node_count(), false);
  map::NodeIndex at = from;
  while (at != nav_target_ && !seen[at] && route.size() < map_.node_count()) {
    seen[at] = true;
    const std::optional<map::EdgeIndex> e = policy.next_edge(at);
    if (!e) break;
    route.push_back(*e);
    at = map_.to_index(*e);
  }
  return route;
}

// A task's navigation fails with `reason`; a trip of the executor's own (to the dock) is dropped,
// and the executor looks again after a slot.
void Executor::abandon_navigation(Outcome outcome, const std::string& reason) {
  if (phase_ == Phase::kNavigating) {
    finish_task(TaskState::kFailed, outcome, reason);
  } else {
    phase_ = Phase::kIdle;
    wait_timer_ = clock_.schedule_after(options_.slot_width, [this] { kick(); });
  }
}

void Executor::on_edge_finished(const EdgeAttempt& a) {
  const map::Edge& edge = map_.edge(a.edge);
  stats_.travelling += a.duration;
  if (is_learning_data(a.outcome)) {
    learn_from(a);
  } else {
    // A cancelled attempt or one cut by a fault says nothing about the way: the event log only.
    const std::string what = fmt::format("edge {} {} after {}{}{}", edge.id, to_string(a.outcome),
                                         format_duration(std::chrono::round<std::chrono::seconds>(a.duration)),
                                         a.message.empty() ? "" : ": ", a.message);
    if (current_)
      book_.note(*current_, "edge", a.outcome == EdgeOutcome::kCancelled ? Outcome::kCancelled : Outcome::kRobotFault, what);
    else
      book_.note_robot("edge", a.outcome == EdgeOutcome::kCancelled ? Outcome::kCancelled : Outcome::kRobotFault, what);
  }
  save_robot_state();
  if (a.outcome == EdgeOutcome::kCancelled) {
    handle_cancelled();
    return;
  }
  if (phase_ != Phase::kNavigating && phase_ != Phase::kDocking) return;
  if (robot_.busy()) return;  // more of a committed route to come
  if (a.outcome == EdgeOutcome::kFailed) ++failed_edges_;
  step_navigation();
}

// Experience of the way: the traversal log, which the nightly refit reads, and the online model of
// the edge, which the next estimate reads.
void Executor::learn_from(const EdgeAttempt& a) {
  const map::Edge& edge = map_.edge(a.edge);
  const Traversal t{.edge_id = edge.id,
                    .from = edge.from,
                    .to = edge.to,
                    .start = a.start,
                    .duration = a.duration,
                    .success = a.succeeded()};
  if (auto ok = store::add_traversal(store_, t); !ok) book_.write_error(ok.error().message);
  models_->observe(
      a.edge,
      {.start = a.start, .end = a.start + a.duration, .seconds = to_seconds(a.duration), .success = a.succeeded()});
  ++stats_.navigation_attempts;
  if (a.succeeded()) ++stats_.navigation_successes;
}

Duration Executor::offline_estimate(map::NodeIndex from, map::NodeIndex to) const {
  if (!options_.online_model) return travel_->travel(from, to, clock_.now());
  return offline_travel_->travel(from, to, clock_.now());
}

void Executor::arrived() {
  if (nav_monitor_ != 0) clock_.cancel(nav_monitor_);
  nav_monitor_ = 0;
  nav_due_.left.reset();
  if (phase_ == Phase::kDocking) {
    phase_ = Phase::kIdle;
    next();
    return;
  }
  navigations_.push_back({.task = *current_,
                          .start = nav_start_,
                          .expected = nav_expected_,
                          .offline_expected = nav_offline_expected_,
                          .actual = clock_.now() - nav_start_,
                          .arrived = true});
  overrun_pending_.reset();  // a navigation overrun noted while not interruptible is moot now
  start_actions();
}

void Executor::go_to_dock() {
  const map::NodeIndex here = robot_.location();
  if (here == options_.dock) {
    phase_ = Phase::kIdle;
    return;
  }
  begin_navigation(options_.dock, travel_->travel(here, options_.dock, clock_.now()));
}

}  // namespace rondo::exec
