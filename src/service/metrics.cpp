// /metrics in the Prometheus text format: request counts and latency by route (here), and the
// executive's figures (tasks by state, scheduler calls, the robot) read on the clock's thread.
#include <fmt/format.h>
#include <malloc.h>

#include <array>

#include "api.h"
#include "rondo/exec/map_travel.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"

namespace rondo::service {
namespace {

constexpr std::array<double, 10> kBounds = {0.001, 0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.5, 1, 5};

std::string label(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\\' || c == '"') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

void RequestMetrics::record(const std::string& route, int status, double seconds) {
  std::lock_guard lock(mutex_);
  PathMetrics& r = routes_[route];
  if (r.buckets.empty()) r.buckets.assign(kBounds.size(), 0);
  ++r.by_status[status];
  ++r.count;
  r.seconds += seconds;
  for (std::size_t i = 0; i < kBounds.size(); ++i)
    if (seconds <= kBounds[i]) ++r.buckets[i];
}

std::string RequestMetrics::prometheus() const {
  std::lock_guard lock(mutex_);
  std::string out =
      "# HELP rondo_http_requests_total HTTP requests answered, by route and status.\n"
      "# TYPE rondo_http_requests_total counter\n";
  for (const auto& [route, r] : routes_)
    for (const auto& [status, n] : r.by_status)
      out += fmt::format("rondo_http_requests_total{{route=\"{}\",status=\"{}\"}} {}\n", label(route), status, n);
  out +=
      "# HELP rondo_http_request_seconds Time to answer a request, by route.\n"
      "# TYPE rondo_http_request_seconds histogram\n";
  for (const auto& [route, r] : routes_) {
    for (std::size_t i = 0; i < kBounds.size(); ++i)
      out += fmt::format("rondo_http_request_seconds_bucket{{route=\"{}\",le=\"{}\"}} {}\n", label(route), kBounds[i],
                         r.buckets[i]);
    out += fmt::format("rondo_http_request_seconds_bucket{{route=\"{}\",le=\"+Inf\"}} {}\n", label(route), r.count);
    out += fmt::format("rondo_http_request_seconds_sum{{route=\"{}\"}} {}\n", label(route), r.seconds);
    out += fmt::format("rondo_http_request_seconds_count{{route=\"{}\"}} {}\n", label(route), r.count);
  }
  return out;
}

Reply metrics_reply(Api& api) {
  Reply reply = api.on_clock([&api] {
    std::map<std::string, int> by_state;
    for (TaskState s : {TaskState::kQueued, TaskState::kWaiting, TaskState::kNavigating, TaskState::kActing,
                        TaskState::kSucceeded, TaskState::kFailed, TaskState::kCancelled, TaskState::kDropped})
      by_state[to_string(s)] = 0;
    // The store's states (the executor keeps only the tasks not finished in memory).
    if (auto stored = store::count_tasks_by_state(api.ctx.store))
      for (const auto& [state, n] : *stored) by_state[state] = static_cast<int>(n);
    const exec::ExecutorStats& st = api.ctx.executor.stats();
    const exec::Robot& robot = api.ctx.robot;
    std::string out =
        "# HELP rondo_tasks Tasks the executor holds, by state.\n"
        "# TYPE rondo_tasks gauge\n";
    for (const auto& [state, n] : by_state) out += fmt::format("rondo_tasks{{state=\"{}\"}} {}\n", state, n);
    out += fmt::format(
        "# HELP rondo_schedule_calls_total Scheduler calls.\n# TYPE rondo_schedule_calls_total counter\n"
        "rondo_schedule_calls_total {}\n"
        "# HELP rondo_refits_total Nightly refits of the edge models.\n# TYPE rondo_refits_total counter\n"
        "rondo_refits_total {}\n"
        "# HELP rondo_navigation_attempts_total Navigations to a task's place.\n"
        "# TYPE rondo_navigation_attempts_total counter\nrondo_navigation_attempts_total {}\n"
        "# HELP rondo_robot_battery Battery charge, 0..1.\n# TYPE rondo_robot_battery gauge\nrondo_robot_battery {}\n"
        "# HELP rondo_robot_charging 1 while on the charger.\n# TYPE rondo_robot_charging gauge\nrondo_robot_charging "
        "{}\n"
        "# HELP rondo_robot_busy 1 while driving or acting.\n# TYPE rondo_robot_busy gauge\nrondo_robot_busy {}\n"
        "# HELP rondo_robot_fault 1 while the robot reports a fault.\n# TYPE rondo_robot_fault gauge\n"
        "rondo_robot_fault {}\n"
        "# HELP rondo_store_write_errors Store writes that failed.\n# TYPE rondo_store_write_errors gauge\n"
        "rondo_store_write_errors {}\n"
        "# HELP rondo_background_schedules_total Reschedules solved on the worker thread.\n"
        "# TYPE rondo_background_schedules_total counter\nrondo_background_schedules_total {}\n"
        "# HELP rondo_background_stale_total Of those, answers not applied: the book had moved on.\n"
        "# TYPE rondo_background_stale_total counter\nrondo_background_stale_total {}\n",
        st.schedules, api.ctx.fleet.refits(), st.navigation_attempts, robot.battery(), robot.charging() ? 1 : 0,
        robot.busy() ? 1 : 0, robot.fault() ? 1 : 0, api.ctx.fleet.write_errors().size(), st.background_runs,
        st.background_stale);
    // What the process holds (docs/operations.md, "Memory over time"): tasks and navigation
    // records in memory, the executor's travel caches, and the heap as glibc's malloc counts it.
    const exec::TravelCache& travel = api.ctx.fleet.travel_cache();
    const struct mallinfo2 heap = ::mallinfo2();
    out += fmt::format(
        "# HELP rondo_memory_tasks Tasks held in the executor's memory (the unfinished ones).\n"
        "# TYPE rondo_memory_tasks gauge\nrondo_memory_tasks {}\n"
        "# HELP rondo_memory_navigations Navigation records held in memory.\n"
        "# TYPE rondo_memory_navigations gauge\nrondo_memory_navigations {}\n"
        "# HELP rondo_memory_travel_policies Policies held by the executor's travel cache.\n"
        "# TYPE rondo_memory_travel_policies gauge\nrondo_memory_travel_policies {}\n"
        "# HELP rondo_memory_background_travel_policies Policies held by the background scheduler's travel cache.\n"
        "# TYPE rondo_memory_background_travel_policies gauge\nrondo_memory_background_travel_policies {}\n"
        "# HELP rondo_memory_travel_slots Time slots whose travel model the executor's planner holds.\n"
        "# TYPE rondo_memory_travel_slots gauge\nrondo_memory_travel_slots {}\n"
        "# HELP rondo_memory_heap_bytes Heap bytes in use (malloc).\n"
        "# TYPE rondo_memory_heap_bytes gauge\nrondo_memory_heap_bytes {}\n"
        "# HELP rondo_memory_heap_free_bytes Heap bytes free but not returned to the system.\n"
        "# TYPE rondo_memory_heap_free_bytes gauge\nrondo_memory_heap_free_bytes {}\n"
        "# HELP rondo_memory_sqlite_bytes Of the heap in use, what SQLite holds (page caches).\n"
        "# TYPE rondo_memory_sqlite_bytes gauge\nrondo_memory_sqlite_bytes {}\n"
        "# HELP rondo_memory_http_threads HTTP threads running (started when needed, ended when idle).\n"
        "# TYPE rondo_memory_http_threads gauge\nrondo_memory_http_threads {}\n",
        api.ctx.fleet.tasks().size(), api.ctx.executor.navigations().size(), travel.cached_count(),
        api.ctx.executor.stats().background_travel_policies, travel.planner().cached_slot_count(),
        heap.uordblks + heap.hblkhd, heap.fordblks, store::Store::sqlite_memory_bytes(), api.http_threads.load());
    Reply r;
    r.text = std::move(out);
    r.content_type = "text/plain; version=0.0.4";
    return r;
  });
  if (reply.content_type != "application/json") {
    reply.text += fmt::format(
        "# HELP rondo_event_streams Open event streams.\n# TYPE rondo_event_streams gauge\nrondo_event_streams {}\n",
        api.streams.load());
    reply.text += api.metrics.prometheus();
    if (api.ctx.role) reply.text += api.ctx.role->prometheus();
  }
  return reply;
}

}  // namespace rondo::service
