// The executor listening to its robot: every edge attempt logged (the traversal log for learning
// data, the event log for the rest), answers forwarded to the running step, observations and the
// battery written to the store, and faults that pause dispatch and hold the monitors still.
#include <fmt/format.h>

#include <algorithm>

#include "attempt_laws.h"
#include "charging.h"
#include "dispatcher.h"
#include "door_models.h"
#include "loading_times.h"
#include "rondo/exec/executor.h"
#include "rondo/store/observations.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/traversal_log.h"
#include "steps.h"
#include "task_run.h"
#include "text.h"
#include "traffic_link.h"

namespace rondo::exec {

void Executor::learn_from(const EdgeAttempt& a) {
  const map::Edge& edge = map_.edge(a.edge);
  if (is_learning_data(a.outcome)) {
    // Experience of the way: the traversal log, which the models learn from.
    const Traversal t{.edge_id = edge.id,
                      .from = edge.from,
                      .to = edge.to,
                      .start = a.start,
                      .duration = a.duration,
                      .success = a.succeeded(),
                      .robot = options_.robot_name,
                      .waited = traffic_ ? traffic_->take_waited(map_.from_index(a.edge)) : Duration{0}};
    if (auto ok = store::add_traversal(store_, t); !ok) book_.write_error(ok.error().message);
    // The online model of the edge, in the fleet's standard time: the next estimate reads it.
    models_.observe(a.edge, {.start = a.start,
                             .end = a.start + a.duration,
                             .seconds = building_.speeds.standard_seconds(options_.robot_name, to_seconds(a.duration)),
                             .success = a.succeeded()});
    ++stats_.navigation_attempts;
    if (a.succeeded()) ++stats_.navigation_successes;
    // A failed door edge is weak evidence of a shut door (door_models.h); what the door model
    // takes of it is stored as a door observation, so that a restart learns the same.
    if (!a.succeeded() && edge.door && door_models_.observe_failed_edge(*edge.door, a.start + a.duration)) {
      const store::Observation o{.what = std::string(Observation::kDoorOpen), .where = *edge.door,
                                 .when = a.start + a.duration, .value = 0,
                                 .text = fmt::format("inferred from a failed attempt at edge {} (weak evidence)", edge.id),
                                 .robot = options_.robot_name};
      if (auto ok = store::add_observation(store_, o); !ok) book_.write_error(ok.error().message);
    }
    return;
  }
  // An attempt the navigation monitor stopped had run this long and would have run longer: kept
  // apart from the traversal log (it says nothing of whether the way was passable) as a lower
  // bound of the edge's long attempts, for the travel-time distribution (attempt_laws.h).
  if (a.outcome == EdgeOutcome::kCancelled && run_ && run_->stop_kind() == TaskRun::Stop::kOverrun &&
      a.duration > Duration{0}) {
    const store::Observation o{.what = kStoppedAttempt, .where = edge.id, .when = a.start,
                               .value = to_seconds(a.duration), .text = run_->id(), .robot = options_.robot_name};
    if (auto ok = store::add_observation(store_, o); !ok) book_.write_error(ok.error().message);
  }
  // A cancelled attempt or one cut by a fault says nothing about the way: the event log only.
  const Outcome code = a.outcome == EdgeOutcome::kCancelled ? Outcome::kCancelled : Outcome::kRobotFault;
  const std::string what = fmt::format("edge {} {} after {}{}{}", edge.id, to_string(a.outcome),
                                       duration_text(a.duration), a.message.empty() ? "" : ": ", a.message);
  if (run_)
    book_.note(run_->id(), EventKind::kEdge, code, what);
  else
    book_.note_robot(options_.robot_name, EventKind::kEdge, code, what);
}

void Executor::on_edge_finished(const EdgeAttempt& a) {
  retired_runs_.clear();
  retired_steps_.clear();
  stats_.travelling += a.duration;
  charging_->watch().edge_finished(a);
  read_battery();
  learn_from(a);
  charging_->crossed(a);
  save_robot_state();
  if (run_) {
    if (Step* s = run_->current()) s->on_edge_finished(a);
  } else if (trip_) {
    trip_->on_edge_finished(a);
  } else if (a.outcome == EdgeOutcome::kCancelled) {
    next();
  }
  check_battery();
}

// A loading or unloading time is experience of the person at that place: learned, and kept in the
// store's observations (what "<action> time", where the place, the seconds).
// An action the overrun monitor stopped is a lower bound of how long the person takes: learned as
// a sample of that length (so the expectation, and with it the monitor's limit, grows until the
// person can finish); one stopped for any other reason says nothing.
void Executor::learn_from(const ActionResult& result) {
  if (!run_ || !loading_.learns(result.name)) return;
  const bool overran = result.outcome == ActionOutcome::kCancelled && run_->stop_kind() == TaskRun::Stop::kOverrun;
  const bool done = result.outcome == ActionOutcome::kSucceeded || result.outcome == ActionOutcome::kFailed;
  if (!done && !overran) return;
  const TaskRecord& r = book_.at(run_->id());
  const std::string& place = map_.node(robot_.location()).name;
  const Duration declared = r.task.duration / static_cast<std::int64_t>(r.action_count());
  if (overran)  // the person had not finished: a lower bound of their time, which raises the estimate
    loading_.observe_stopped(result.name, place, declared, result.duration, result.start);
  else
    loading_.observe(result.name, place, declared, result.duration, result.outcome != ActionOutcome::kFailed,
                      result.start);
  if (result.outcome != ActionOutcome::kSucceeded) return;
  const store::Observation o{.what = result.name + " time", .where = place, .when = clock_.now(),
                             .value = to_seconds(result.duration), .text = r.task.id, .robot = options_.robot_name};
  if (auto ok = store::add_observation(store_, o); !ok) book_.write_error(ok.error().message);
}

std::vector<map::EdgeIndex> Executor::route() {
  const NavigateStep* navigation = trip_.get();
  if (run_) navigation = dynamic_cast<const NavigateStep*>(run_->current());
  if (const auto* spec = run_ ? dynamic_cast<const SpecStep*>(run_->current()) : nullptr)
    return spec->planned_route();  // a spec task's journey: the product policy's way to satisfaction
  if (navigation == nullptr) return {};
  std::vector<map::EdgeIndex> edges;
  for (const plan::PolicyStep& s : planner_.policy(navigation->target(), clock_.now()).route(robot_.location()))
    edges.push_back(s.edge);
  return edges;
}

std::vector<LearnedActionTime> Executor::loading_times() const { return loading_.entries(); }

void Executor::refresh_learned_durations(const std::vector<TaskId>& ids) {
  for (const TaskId& id : ids) {
    TaskRecord& r = book_.at(id);
    if (r.task.actions.empty() || r.task.start_node.empty()) continue;
    const Duration share = r.task.duration / static_cast<std::int64_t>(r.action_count());
    Duration total{0}, patience{0};
    bool learned = false, slow = false;
    for (const Action& a : r.task.actions) {
      if (!loading_.learns(a.name)) {
        total += share;
        patience += share;
        continue;
      }
      const Duration e = loading_.expected(a.name, r.task.start_node, share);
      learned = learned || e != share;
      total += e;
      const std::optional<Duration> q = options_.person_patience > 0
                                            ? loading_.quantile(a.name, r.task.start_node, share, options_.person_patience)
                                            : std::nullopt;
      slow = slow || q.has_value();
      patience += q.value_or(e);
    }
    r.patience = slow ? std::optional<Duration>(patience) : std::nullopt;
    // Never past its window: a task that fits as declared is not made impossible by a guess.
    if (learned && r.task.window) total = std::min(total, r.task.window->deadline - r.task.window->release);
    r.learned_duration = learned ? std::optional<Duration>(total) : std::nullopt;
  }
}

void Executor::on_action_finished(const ActionResult& reported) {
  const ActionResult result = confirmed_result(reported);
  retired_runs_.clear();
  retired_steps_.clear();
  stats_.acting += result.duration;
  charging_->watch().action_finished(result);
  read_battery();
  learn_from(result);
  if (run_) {
    if (Step* s = run_->current()) s->on_action_finished(result);
  } else if (result.outcome == ActionOutcome::kCancelled) {
    next();
  }
  check_battery();
}

void Executor::on_interruptible_changed(bool interruptible) {
  if (!run_ || run_->set_robot_interruptible(interruptible) || !interruptible) return;
  if (charging_->low()) return charge_now();  // the charge waited for this moment
  if (!running_standard() || !interruptible_now()) return;
  if (const std::optional<TaskId> ready = dispatcher_->ready_on_demand(clock_.now())) preempt_for_on_demand(*ready);
}

void Executor::log_battery() {
  const store::Observation o{.what = "battery", .where = map_.node(robot_.location()).name, .when = clock_.now(),
                             .value = std::clamp(robot_.battery(), 0.0, 1.0), .text = std::nullopt,
                             .robot = options_.robot_name};
  if (auto ok = store::add_observation(store_, o); !ok) book_.write_error(ok.error().message);
  save_battery();  // what the estimator learned, at the end of every task
}

void Executor::save_robot_state() {
  const std::optional<map::Pose> pose = robot_.position();
  store::RobotState st{.robot = options_.robot_name,
                       .node = map_.node(robot_.location()).name,
                       .battery = std::clamp(robot_.battery(), 0.0, 1.0),
                       .updated = clock_.now()};
  if (pose) {
    st.x = pose->x;
    st.y = pose->y;
    st.yaw = pose->yaw;
  }
  if (fault_) st.fault = fault_->message;
  if (auto ok = store::save_robot_state(store_, st); !ok) book_.write_error(ok.error().message);
}

void Executor::observe(Observation observation) {
  if (observation.source.empty()) observation.source = "building";
  on_observation(observation);
}

void Executor::on_observation(const Observation& seen) {
  // The building's observations are stored without a robot, with the sensor named in the text.
  std::string text = seen.text;
  if (!seen.source.empty()) text = "from " + seen.source + (text.empty() ? "" : ": " + text);
  const store::Observation o{.what = seen.what, .where = seen.where, .when = seen.when, .value = seen.value,
                             .text = text.empty() ? std::nullopt : std::optional<std::string>(text),
                             .robot = seen.source.empty() ? options_.robot_name : std::string()};
  if (auto ok = store::add_observation(store_, o); !ok) book_.write_error(ok.error().message);
  if (!started_ || seen.what != Observation::kDoorOpen) return;
  ++assumption_stats_.door_observations;
  if (seen.value < 0.5)
    door_seen_closed(seen);  // executor_observations.cpp
  else
    door_seen_open(seen);
}

void Executor::on_fault(const RobotFault& fault) {
  const bool first = !fault_;
  fault_ = fault;
  if (!first) return;
  in_fault_ = true;
  fault_since_ = clock_.now();
  save_robot_state();
  book_.note_robot(options_.robot_name, EventKind::kFault, Outcome::kRobotFault,
                   fmt::format("{}: {}; dispatch paused", to_string(fault.kind), fault.message));
  if (run_) {
    if (Step* s = run_->current()) s->suspend();
  } else if (trip_) {
    trip_->suspend();
  } else if (look_again_ != 0) {  // idle: ready() looks again instead
    clock_.cancel(look_again_);
    look_again_ = 0;
  }
  if (unable_) unable_();
}

void Executor::on_ready() {
  if (!fault_) return;
  retired_runs_.clear();
  retired_steps_.clear();
  const Duration down = clock_.now() - fault_since_.value_or(clock_.now());
  fault_.reset();
  fault_since_.reset();
  in_fault_ = false;
  book_.note_robot(options_.robot_name, EventKind::kReady, Outcome::kRobotReady,
                   fmt::format("ready again after {}; dispatch resumes", duration_text(down)));
  if (run_) {
    if (Step* s = run_->current()) s->resume();
    return;
  }
  if (trip_) return trip_->resume();
  kick();
}

}  // namespace rondo::exec
