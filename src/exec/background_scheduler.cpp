#include "background_scheduler.h"

#include <utility>

#include "rondo/schedule/stop_condition.h"

namespace rondo::exec {
namespace {

using Steady = std::chrono::steady_clock;

double steady_seconds() {
  return std::chrono::duration<double>(Steady::now().time_since_epoch()).count();
}

// Stops a solve when the worker is asked to stop.
class TokenStop final : public schedule::StopCondition {
 public:
  explicit TokenStop(std::stop_token token) : token_(std::move(token)) {}
  bool should_stop() const override { return token_.stop_requested(); }

 private:
  std::stop_token token_;
};

}  // namespace

BackgroundScheduler::BackgroundScheduler(Clock& clock, const map::TopoMap& map, schedule::Scheduler& scheduler,
                                         Options options, std::function<void(ScheduleAnswer)> on_answer,
                                         std::function<void()> on_ready)
    : clock_(clock),
      map_(map),
      scheduler_(scheduler),
      options_(options),
      on_answer_(std::move(on_answer)),
      on_ready_(std::move(on_ready)),
      models_(std::make_shared<plan::LearnedEdgeModels>(map, nullptr)),
      planner_(std::make_unique<plan::TravelPlanner>(map_, models_,
                                                     planner_options(options_.slot_width))),
      travel_(std::make_unique<TravelCache>(map_, models_, *planner_, options_.slot_width, options_.route_threshold)),
      rng_(options.seed),
      worker_([this](std::stop_token stop) { work(std::move(stop)); }) {}

BackgroundScheduler::~BackgroundScheduler() {
  worker_.request_stop();  // wakes the worker's waits (condition_variable_any with its token)
  worker_.join();
  *alive_ = false;
}

void BackgroundScheduler::submit(ScheduleJob job) {
  ready_ = false;
  {
    std::lock_guard lock(mutex_);
    job_ = std::move(job);
  }
  wake_.notify_one();
}

void BackgroundScheduler::work(std::stop_token stop) {
  for (;;) {
    std::optional<ScheduleJob> job;
    {
      std::unique_lock lock(mutex_);
      if (!wake_.wait(lock, stop, [this] { return job_.has_value(); })) return;  // stop requested
      job = std::move(job_);
      job_.reset();
    }
    const Steady::time_point handed_over = Steady::now();
    ScheduleAnswer answer = solve(*job, stop);
    if (stop.stop_requested()) return;
    clock_.post([alive = alive_, this, answer = std::move(answer)]() mutable {
      if (*alive) on_answer_(std::move(answer));
    });
    {
      // The rest of the interval: what is asked for meanwhile waits, and goes in one problem.
      std::unique_lock lock(mutex_);
      wake_.wait_until(lock, stop, handed_over + options_.min_interval, [] { return false; });
    }
    if (stop.stop_requested()) return;
    clock_.post([alive = alive_, this] {
      if (!*alive) return;
      ready_ = true;
      on_ready_();
    });
  }
}

ScheduleAnswer BackgroundScheduler::solve(ScheduleJob& job, std::stop_token stop) {
  const double start = steady_seconds();
  // The worker's models become the copy: its planner and cache keep what the edges observed since
  // their last problem did not change (or drop everything after a refit), as with the live models.
  *models_ = *job.models;
  schedule::TryScheduleRequest& request = job.problem.request;
  set_travel(request.problem, *travel_, job.problem.nodes, job.problem.risk_alpha, job.problem.specs, job.problem.speed,
             job.problem.stops);
  const schedule::DeadlineStop budget(steady_seconds, start + std::chrono::duration<double>(options_.budget).count());
  const TokenStop cancelled(std::move(stop));
  const schedule::AnyStop either({&budget, &cancelled});
  ScheduleAnswer answer{.generation = job.generation,
                        .result = solve_planned(job.problem, scheduler_, options_.polls, &either, rng_)};
  answer.seconds = steady_seconds() - start;
  answer.travel_policies = travel_->cached_count();
  return answer;
}

}  // namespace rondo::exec
