#include <fmt/format.h>

#include "steps.h"
#include "text.h"

namespace rondo::exec {

WaitStep::WaitStep(StepContext& ctx, StepHooks hooks, TaskId task, EarlyWait wait)
    : Step(ctx, std::move(hooks)), task_(std::move(task)), wait_(std::move(wait)) {}

WaitStep::~WaitStep() { stop_timer(); }

void WaitStep::start() {
  since_ = ctx_.clock.now();
  const TaskRecord& r = ctx_.book.at(task_);
  const std::string& here = ctx_.map.node(ctx_.robot.location()).name;
  ctx_.book.transition(
      task_, TaskState::kWaiting, Outcome::kEarly,
      wait_.behind.empty()
          ? fmt::format("early: waits {} at {} so as to arrive at {} when {} at {}",
                        duration_text(wait_.until - since_), here, r.task.start_node,
                        r.release() > r.task.window->release ? "it may start again" : "the window opens",
                        ctx_.clock_text(r.release()))
          : fmt::format("early: waits {} at {} so as to arrive at {} when it is free: {}",
                        duration_text(wait_.until - since_), here, r.task.start_node, wait_.behind));
  arm();
}

// When the time comes, another robot may have set out for the place meanwhile: the robot waits
// on, saying for whom, until that robot is expected to have left.
void WaitStep::arm() {
  timer_ = ctx_.clock.schedule_at(wait_.until, [this] {
    timer_ = 0;
    const Time now = ctx_.clock.now();
    if (wait_.longer)
      if (const std::optional<PutOff> later = wait_.longer(); later && later->depart > now) {
        ctx_.book.note(task_, EventKind::kWaitsLonger, Outcome::kEarly,
                       fmt::format("waits {} more at {}: {}", duration_text(later->depart - now),
                                   ctx_.map.node(ctx_.robot.location()).name, later->behind));
        wait_.until = later->depart;
        return arm();
      }
    ctx_.stats.waiting += now - since_;
    end({.status = StepEnd::Status::kDone});
    if (wait_.set_out) wait_.set_out();
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
