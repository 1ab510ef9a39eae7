#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "found_blocked.h"
#include "spec_tasks.h"
#include "steps.h"
#include "text.h"

namespace rondo::exec {

SpecStep::SpecStep(StepContext& ctx, StepHooks hooks, TaskId task)
    : RobotStep(ctx, std::move(hooks)), task_(std::move(task)) {}

Result<plan::SpecPlan> SpecStep::plan_here(Time now) const {
  std::vector<map::EdgeIndex> held;
  for (map::EdgeIndex e = 0; e < ctx_.map.edge_count(); ++e)
    if (ctx_.found_blocked.held_until(e, now)) held.push_back(e);
  return ctx_.specs.plan_now(ctx_.book.at(task_).task.spec, ctx_.robot.location(), state_, now, held);
}

void SpecStep::start() {
  const Time now = ctx_.clock.now();
  const map::NodeIndex here = ctx_.robot.location();
  started_ = now;
  target_ = here;
  const TaskRecord& r = ctx_.book.at(task_);
  if (auto p = ctx_.specs.planner(r.task.spec); !p) {
    return end({.status = StepEnd::Status::kFailed,
                .outcome = Outcome::kSpecUnsatisfiable,
                .reason = fmt::format("spec unsatisfiable: {}", p.error().message)});
  }
  state_ = ctx_.specs.state_at(r, here);  // the node it starts (or goes on) from is read first
  ctx_.book.set_spec_state(task_, state_);
  const plan::SpecPlanner& planner = **ctx_.specs.planner(r.task.spec);
  if (planner.automaton().accepting(state_)) {
    ctx_.book.set_spec_state(task_, state_, ctx_.map.node(here).name);
    return end({.status = StepEnd::Status::kDone});
  }
  Result<plan::SpecPlan> plan = plan_here(now);
  if (!plan) {
    return end({.status = StepEnd::Status::kFailed,
                .outcome = Outcome::kSpecUnsatisfiable,
                .reason = fmt::format("spec unsatisfiable: {}", plan.error().message)});
  }
  if (plan->unsatisfiable) return cannot(*plan, false);
  expected_ = from_seconds(plan->expected_seconds());
  target_ = plan->end_node().value_or(here);
  std::string route = ctx_.map.node(here).name;
  for (const plan::ProductStep& s : plan->policy().route(here, state_))
    route += fmt::format(" > {}", ctx_.map.node(s.to).name);
  ctx_.book.transition(task_, TaskState::kNavigating, Outcome::kDeparted,
                       fmt::format("spec {}: route {} (satisfied at {}), expected travel {}", r.task.spec, route,
                                   ctx_.map.node(target_).name, duration_text(expected_)));
  const ExecutorOptions& o = ctx_.options;
  monitor_.arm(Monitor::limit("navigation overrun: still travelling", "the expected travel time", expected_,
                              o.navigation_overrun, o.navigation_slack),
               [this](const std::string& why) { hooks_.overrun(Outcome::kNavigationOverrun, why); });
  if (ctx_.in_fault) monitor_.suspend();
  advance();
}

std::vector<map::EdgeIndex> SpecStep::planned_route() const {
  std::vector<map::EdgeIndex> edges;
  const Result<plan::SpecPlan> plan = plan_here(ctx_.clock.now());
  if (!plan || plan->unsatisfiable) return edges;
  for (const plan::ProductStep& s : plan->policy().route(ctx_.robot.location(), state_)) edges.push_back(s.edge);
  return edges;
}

void SpecStep::cannot(const plan::SpecPlan& plan, bool held) {
  monitor_.cancel();
  const std::string why = plan.unsatisfiable ? plan.unsatisfiable->reason : "the formula cannot be satisfied";
  if (held) {  // only because of edges found blocked: the task may wait for them
    const bool wait = ctx_.options.blocked_edge == ExecutorOptions::BlockedEdge::kWait;
    return end({.status = wait ? StepEnd::Status::kBlocked : StepEnd::Status::kFailed,
                .outcome = Outcome::kNoRouteNow,
                .reason = fmt::format("no route now: {} (with the edges found blocked left out)", why),
                .edge = edge_});
  }
  // Edges closed now (the models' answer at this time) are no route, not a formula that cannot be.
  if (plan.unsatisfiable && plan.unsatisfiable->cause == plan::Unsatisfiable::Cause::kUnreachable)
    return end(
        {.status = StepEnd::Status::kFailed, .outcome = Outcome::kNoRoute, .reason = fmt::format("no route: {}", why)});
  end({.status = StepEnd::Status::kFailed,
       .outcome = Outcome::kSpecUnsatisfiable,
       .reason = fmt::format("spec unsatisfiable: {}", why)});
}

void SpecStep::advance() {
  const map::NodeIndex here = ctx_.robot.location();
  const Time now = ctx_.clock.now();
  const plan::SpecPlanner& planner = **ctx_.specs.planner(ctx_.book.at(task_).task.spec);
  if (planner.automaton().accepting(state_)) {
    monitor_.cancel();
    target_ = here;
    ctx_.book.at(task_).spec_journey = std::make_pair(expected_, now - started_);
    ctx_.book.set_spec_state(task_, state_, ctx_.map.node(here).name);
    return end({.status = StepEnd::Status::kDone});
  }
  if (ctx_.in_fault) return;  // resume() goes on from where the robot is
  if (failed_edges_ >= ctx_.options.max_failed_edges) {
    return end({.status = StepEnd::Status::kFailed,
                .outcome = Outcome::kNavigationGaveUp,
                .reason = fmt::format("navigation gave up: {} failed edge attempts near {}", failed_edges_,
                                      ctx_.map.node(here).name)});
  }
  Result<plan::SpecPlan> plan = plan_here(now);
  if (!plan) {
    return end({.status = StepEnd::Status::kFailed,
                .outcome = Outcome::kSpecUnsatisfiable,
                .reason = fmt::format("spec unsatisfiable: {}", plan.error().message)});
  }
  if (plan->unsatisfiable || !plan->next_edge()) {
    // Satisfiable with the held edges? Then they are what stops it now.
    const Result<plan::SpecPlan> free = ctx_.specs.plan_now(ctx_.book.at(task_).task.spec, here, state_, now, {});
    return cannot(*plan, free && !free->unsatisfiable);
  }
  std::vector<map::EdgeIndex> route;
  for (const plan::ProductStep& s : plan->policy().route(here, state_)) {
    if (planner.automaton().rejecting(s.next_state)) break;  // never: the policy does not break its formula
    route.push_back(s.edge);
  }
  if (route.empty()) return cannot(*plan, false);
  target_ = plan->end_node().value_or(here);
  edge_ = route.front();
  ctx_.before_command();
  ctx_.robot.drive(Route{.edges = std::move(route), .committed = 1});
}

void SpecStep::on_edge_finished(const EdgeAttempt& a) {
  const Time now = ctx_.clock.now();
  const double p = std::clamp(ctx_.models.outcome(a.edge, now).success_probability, 0.0, 1.0);
  if (a.outcome == EdgeOutcome::kSucceeded) ctx_.found_blocked.passed(a.edge);
  if (a.outcome == EdgeOutcome::kFailed) ctx_.found_blocked.failed(a.edge, edge_ == a.edge ? p : 0.0, now);
  if (a.outcome == EdgeOutcome::kSucceeded) {
    const plan::SpecPlanner& planner = **ctx_.specs.planner(ctx_.book.at(task_).task.spec);
    state_ = planner.after_reaching(state_, ctx_.robot.location());
    ctx_.book.set_spec_state(task_, state_);
  }
  if (a.outcome == EdgeOutcome::kCancelled) return end(halted_end());
  if (ctx_.robot.busy()) return;
  if (halting()) return end(halted_end());
  if (a.outcome == EdgeOutcome::kFailed) {
    ++failed_edges_;
    // Found blocked: a run the live model did not expect, or attempts left unlikely to pass. Every
    // journey holds it so until the live model holds it likely passable again (within a day).
    const FoundBlocked::Run run = ctx_.found_blocked.run(a.edge, now);
    const int tries = ctx_.options.max_failed_edges - failed_edges_;
    if (run.refuted() || (tries > 0 && std::pow(1 - p, tries) > 0.5)) {
      const auto open =
          passable_again(ctx_.models, ctx_.planner, ctx_.options.slot_width, a.edge, now, now + hours(24));
      ctx_.found_blocked.hold(a.edge, open ? open->first : now + hours(24));
      ctx_.book.note(task_, EventKind::kEdge, Outcome::kNoRouteNow,
                     fmt::format("{} found blocked ({} failed attempts in a row): the spec's way is planned again "
                                 "without it",
                                 ctx_.map.edge(a.edge).id, run.failures));
    }
  }
  advance();
}

}  // namespace rondo::exec
