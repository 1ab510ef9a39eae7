#include <fmt/format.h>

#include "steps.h"
#include "text.h"

namespace rondo::exec {

WaitStep::WaitStep(StepContext& ctx, StepHooks hooks, TaskId task, Time until, std::string behind)
    : Step(ctx, std::move(hooks)), task_(std::move(task)), until_(until), behind_(std::move(behind)) {}

WaitStep::~WaitStep() { stop_timer(); }

void WaitStep::start() {
  since_ = ctx_.clock.now();
  const TaskRecord& r = ctx_.book.at(task_);
  const std::string& here = ctx_.map.node(ctx_.robot.location()).name;
  ctx_.book.transition(
      task_, TaskState::kWaiting, Outcome::kEarly,
      behind_.empty() ? fmt::format("early: waits {} at {} so as to arrive at {} when {} at {}",
                                    duration_text(until_ - since_), here, r.task.start_node,
                                    r.release() > r.task.window->release ? "it may start again" : "the window opens",
                                    ctx_.clock_text(r.release()))
                      : fmt::format("early: waits {} at {} so as to arrive at {} when it is free: {}",
                                    duration_text(until_ - since_), here, r.task.start_node, behind_));
  timer_ = ctx_.clock.schedule_at(until_, [this] {
    timer_ = 0;
    ctx_.stats.waiting += ctx_.clock.now() - since_;
    end({.status = StepEnd::Status::kDone});
  });
}

void WaitStep::stop_timer() {
  if (timer_ == 0) return;
  ctx_.clock.cancel(timer_);
  timer_ = 0;
  ctx_.stats.waiting += ctx_.clock.now() - since_;
}

void WaitStep::halt() {
  stop_timer();
  end({.status = StepEnd::Status::kHalted});
}

void WaitStep::abandon() {
  stop_timer();
  end_silently();
}

}  // namespace rondo::exec
