#include "rondo/core/routine.h"

#include <algorithm>

#include <fmt/format.h>

#include "task_problem.h"

namespace rondo {

bool runs_on(const Routine& r, std::chrono::year_month_day day) {
  if (r.first_day && day < *r.first_day) return false;
  if (r.last_day && day > *r.last_day) return false;
  if (std::find(r.dates_off.begin(), r.dates_off.end(), day) != r.dates_off.end()) return false;
  if (r.days.empty()) return true;
  const std::chrono::weekday wd{std::chrono::sys_days{day}};
  return std::find(r.days.begin(), r.days.end(), wd) != r.days.end();
}

namespace {

std::string instance_id(const Routine& r, std::chrono::year_month_day day, Duration start) {
  const auto minutes_of_day = std::chrono::duration_cast<std::chrono::minutes>(start).count();
  return fmt::format("{}@{:04}-{:02}-{:02}T{:02}:{:02}", r.name, static_cast<int>(day.year()),
                     static_cast<unsigned>(day.month()), static_cast<unsigned>(day.day()), minutes_of_day / 60,
                     minutes_of_day % 60);
}

}  // namespace

std::vector<Task> instances_on(const Routine& r, std::chrono::year_month_day day, const TimeZone& zone) {
  std::vector<Task> out;
  if (!runs_on(r, day) || r.window_end <= r.window_start) return out;
  const Duration step = r.every.value_or(r.window_end - r.window_start);
  if (step <= Duration{0}) return out;
  for (Duration from = r.window_start; from < r.window_end; from += step) {
    const Duration to = std::min(from + step, r.window_end);
    const TimeWindow window{zone.at(day, from), zone.at(day, to)};
    if (r.task.duration > window.width()) continue;  // the last, cut-short window may not fit it
    Task t = r.task;
    t.id = instance_id(r, day, from);
    t.kind = TaskKind::kStandard;
    t.window = window;
    out.push_back(std::move(t));
  }
  return out;
}

namespace detail {

std::optional<Problem> first_problem(const Routine& r) {
  if (r.name.empty()) return Problem{"name", "a routine needs a name"};
  if (r.name.find('@') != std::string::npos) return Problem{"name", "a routine name cannot contain '@'"};
  if (r.window_start < Duration{0} || r.window_start >= hours(24)) {
    return Problem{"window.from", "must be a time of day from 00:00 to 23:59"};
  }
  if (r.window_end <= r.window_start) {
    return Problem{"window.to", "the daily window must close after it opens (opens " +
                                    format_time_of_day(r.window_start) + ", closes " + format_time_of_day(r.window_end) + ")"};
  }
  if (r.window_end > hours(24)) return Problem{"window.to", "must be 24:00 at the latest"};
  if (r.every) {
    if (*r.every <= Duration{0}) return Problem{"every", "the repeat interval must be longer than zero"};
    if (*r.every < kMinRoutineEvery) {
      return Problem{"every", "the repeat interval " + format_duration(*r.every) +
                                  " is below the minimum of 1m (instance ids name the minute they start)"};
    }
    if (*r.every > r.window_end - r.window_start) {
      return Problem{"every", "the repeat interval " + format_duration(*r.every) + " is longer than the daily window"};
    }
  }
  if (!r.task.id.empty()) return Problem{"task.id", "a routine's task gets its id from the routine"};
  if (r.task.window) return Problem{"task.window", "a routine's task gets its window from the routine"};
  if (r.task.kind != TaskKind::kStandard) return Problem{"task.kind", "routine tasks are standard tasks"};
  const Duration slot = r.every.value_or(r.window_end - r.window_start);
  if (r.task.duration > slot) {
    return Problem{"task.duration", "duration " + format_duration(r.task.duration) + " does not fit in the " +
                                        format_duration(slot) + " window of each instance"};
  }
  // The rest of the template is checked as an instance would be.
  Task probe = r.task;
  probe.id = r.name;
  probe.window = TimeWindow{Time{}, Time{} + slot};
  if (auto p = first_problem(probe)) return Problem{join_path("task", p->field), p->message};
  if (!r.task.after.empty()) return Problem{"task.after", "routine tasks cannot name tasks to come after"};
  if (r.task.delivery) return Problem{"task.delivery", "deliveries are jobs of two tasks, not routines"};
  if (r.first_day && r.last_day && *r.last_day < *r.first_day) {
    return Problem{"last_day", "the last day is before the first"};
  }
  return std::nullopt;
}

}  // namespace detail

Status validate(const Routine& r, const std::string& path) {
  if (auto p = detail::first_problem(r)) return Error::invalid(detail::join_path(path, p->field) + ": " + p->message);
  return {};
}

}  // namespace rondo
