// Routines: rules that create the same tasks every day (MISSION.md §1), e.g. "check the emergency
// exits every 2 hours from 08:00 to 18:00 on week days, not on bank holidays".
//
//   Routine r;
//   r.name = "exit-checks";
//   r.task = exit_check_template;            // id and window are filled in per instance
//   r.window_start = hours(8);  r.window_end = hours(18);  r.every = hours(2);
//   r.days = {Monday, Tuesday, Wednesday, Thursday, Friday};
//   std::vector<Task> today = instances_on(r, year{2026}/11/23, *TimeZone::named("Europe/London"));
//
// Times of day are local to the deployment's time zone, so a routine at 09:00 runs at 09:00 in
// winter and in summer.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/task.h"
#include "rondo/core/time.h"
#include "rondo/core/timezone.h"

namespace rondo {

// The shortest repeat interval: instance ids name the local minute an instance starts, so they are
// unique within a day only when instances start at least a minute apart.
inline constexpr Duration kMinRoutineEvery = std::chrono::minutes(1);

struct Routine {
  std::string name;   // unique; instance ids are "<name>@<local date>T<hh:mm>"
  Task task;          // the template: everything but id and window
  Duration window_start{0};  // local time of day the daily window opens
  Duration window_end{0};    // and closes (after window_start; at most 24:00)
  // Without `every`, one task a day whose window is the daily window. With it, one task every
  // `every` from window_start, each with the window [start, start + every) cut at window_end.
  std::optional<Duration> every;
  std::vector<std::chrono::weekday> days;                 // empty: every day
  std::vector<std::chrono::year_month_day> dates_off;     // holidays
  std::optional<std::chrono::year_month_day> first_day;   // routine runs from this date
  std::optional<std::chrono::year_month_day> last_day;    // up to and including this date

  bool operator==(const Routine&) const = default;
};

// Whether the routine makes tasks on the local date `day`.
bool runs_on(const Routine& r, std::chrono::year_month_day day);

// The routine's tasks on the local date `day` (none on days off), in start order.
std::vector<Task> instances_on(const Routine& r, std::chrono::year_month_day day, const TimeZone& zone);

// Checks what cannot be meant: no name, a window that ends before it starts or after 24:00, a
// repeat interval under kMinRoutineEvery or longer than the window, a template duration that does not fit
// in an instance's window, a template with a window or an id.
Status validate(const Routine& r, const std::string& path = "");

}  // namespace rondo
