// The executor's daily rhythm: routine tasks created at local midnight for the day ahead, and the
// nightly refit of what the building learned (building_learning.cpp).
#include <fmt/format.h>
#include <malloc.h>

#include <chrono>

#include "rondo/exec/executor.h"

namespace rondo::exec {
namespace {

std::chrono::year_month_day next_day(std::chrono::year_month_day d) {
  return std::chrono::year_month_day{std::chrono::sys_days{d} + std::chrono::days{1}};
}

}  // namespace

void Executor::create_routine_tasks(std::chrono::year_month_day day) {
  std::vector<Task> batch;
  const Time now = clock_.now();
  for (const Routine& r : routines_) {
    // A routine the robot says it cannot run (a deployment's, once its vehicle told what it runs)
    // makes no task that day, with a `rejected` event; the others' tasks are added as always.
    const std::optional<std::string> why = cannot_run(robot_, r.task.actions);
    for (Task& t : instances_on(r, day, zone_)) {
      if (!t.window || t.window->deadline <= now || book_.known(t.id)) continue;
      if (why) {
        book_.note_request(t.id, EventKind::kRejected, Outcome::kInvalidRequest, fmt::format("from routine {}: {}", r.name, *why));
        continue;
      }
      batch.push_back(std::move(t));
    }
  }
  if (batch.empty()) return;
  if (auto ok = add_tasks(std::move(batch), "routine"); !ok) book_.write_error(ok.error().message);
}

void Executor::schedule_midnight() {
  const auto tomorrow = next_day(zone_.local_date(clock_.now()));
  clock_.schedule_at(zone_.at(tomorrow, Duration{0}), [this, tomorrow] {
    create_routine_tasks(tomorrow);
    schedule_midnight();
  });
}

void Executor::schedule_refit() {
  if (!options_.refit_at) return;
  const Time now = clock_.now();
  auto day = zone_.local_date(now);
  Time at = zone_.at(day, *options_.refit_at);
  if (at <= now) at = zone_.at(next_day(day), *options_.refit_at);
  clock_.schedule_at(at, [this] {
    refit();
    // The night's traversal log and tables are freed: hand the free pages back to the system, so
    // a long-lived service's resident memory is what it holds, not its largest night so far.
    ::malloc_trim(0);
    schedule_refit();
  });
}

void Executor::refit() {
  if (building_.refit()) ++stats_.refits;
}

}  // namespace rondo::exec
