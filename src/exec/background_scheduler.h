// The scheduler on a worker thread (ExecutorOptions::background_scheduling, DESIGN.md "Executor"):
// the clock's thread hands over a problem built from the book, with a copy of the edge models
// taken at the same moment; the worker solves it with its own planner and travel cache (kept warm
// across problems: they follow the copies through the models' version, as they follow the live
// models), under the poll budget, a wall-time budget and its stop token, and posts the answer
// back through Clock::post().
//
//   BackgroundScheduler worker(clock, map, scheduler, {...}, [&](ScheduleAnswer a) { ... },
//                              [&] { /* ready for the next problem */ });
//   if (worker.ready()) worker.submit({.generation = g, .problem = std::move(p), .models = copy});
//
// Threads: construction, submit(), ready() and destruction belong to the clock's thread; the two
// callbacks run there too (posted), never after the destructor has started. After each answer the
// worker waits out the rest of `min_interval` (since that problem was handed over) before it says
// it is ready, so that requests meanwhile are merged into one reschedule. The destructor asks the
// worker to stop (a running solve returns its best answer so far, which is not delivered) and
// joins it. The scheduler is used by the worker only, and must outlive this object.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "rondo/exec/clock.h"
#include "rondo/exec/map_travel.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/learned_edge_models.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/schedule/scheduler.h"
#include "rondo/schedule/try_schedule.h"
#include "scheduling.h"

namespace rondo::exec {

struct ScheduleJob {
  std::uint64_t generation = 0;  // the caller's: handed back with the answer
  PendingProblem problem;
  std::shared_ptr<const plan::LearnedEdgeModels> models;  // a copy, as they were when built
};

struct ScheduleAnswer {
  std::uint64_t generation = 0;
  PlannedAnswer result;
  double seconds = 0;  // wall time the solve took
  std::size_t travel_policies = 0;  // the worker's TravelCache::cached_count() after the solve
};

class BackgroundScheduler {
 public:
  struct Options {
    std::int64_t polls = 20'000;                // per solver call, as the synchronous executor
    Duration budget = seconds(2);               // wall time per solve
    Duration min_interval = milliseconds(100);  // wall time from one problem to the next
    Duration slot_width = minutes(15);          // of the worker's planner (ExecutorOptions::slot_width)
    std::optional<Duration> route_threshold{};  // of the worker's travel (ExecutorOptions::route_threshold)
    std::uint64_t seed = 1;                     // of the worker's tie-breaking
  };
  BackgroundScheduler(Clock& clock, const map::TopoMap& map, schedule::Scheduler& scheduler, Options options,
                      std::function<void(ScheduleAnswer)> on_answer, std::function<void()> on_ready);
  ~BackgroundScheduler();
  BackgroundScheduler(const BackgroundScheduler&) = delete;
  BackgroundScheduler& operator=(const BackgroundScheduler&) = delete;

  // True when the worker waits for a problem (none handed over, or its answer was posted and the
  // interval since has passed).
  bool ready() const { return ready_; }
  // Precondition: ready(); job.models non-null.
  void submit(ScheduleJob job);

 private:
  void work(std::stop_token stop);
  ScheduleAnswer solve(ScheduleJob& job, std::stop_token stop);

  Clock& clock_;
  const map::TopoMap& map_;
  schedule::Scheduler& scheduler_;
  Options options_;
  std::function<void(ScheduleAnswer)> on_answer_;
  std::function<void()> on_ready_;
  bool ready_ = true;  // clock's thread
  // Set false by the destructor: callbacks posted earlier and run later do nothing.
  std::shared_ptr<bool> alive_ = std::make_shared<bool>(true);

  // The worker's own view: the models copied in before each solve, read by its planner and cache.
  std::shared_ptr<plan::LearnedEdgeModels> models_;
  std::unique_ptr<plan::TravelPlanner> planner_;
  std::unique_ptr<TravelCache> travel_;
  std::mt19937_64 rng_;

  std::mutex mutex_;
  std::condition_variable_any wake_;
  std::optional<ScheduleJob> job_;  // under mutex_
  std::jthread worker_;             // last: started after everything it reads
};

}  // namespace rondo::exec
