// The per-day schedule picture of `rondo run` (issue 6): one lane per task on an axis of local
// hours, the time window as a light band, the last planned start..end as an outlined bar, what
// really happened as a filled bar coloured by the outcome, the spans on the charger, and a legend.
//
//   DayPicture day{.title = "G4S, day 3", .from = midnight, .to = next_midnight,
//                  .zone = *TimeZone::named("Europe/London")};
//   day.rows.push_back({.task_id = "fd-3", .label = "check fire door 3",
//                       .window = TimeWindow{nine, noon}, .planned = {{t1, t2}},
//                       .actual = {{t1, t3}}, .outcome = "succeeded"});
//   std::ofstream("day-03.svg") << render_day_svg(day);
//
// Contract: the result is a standalone, well-formed SVG 1.1 document (UTF-8) for any input: text is
// escaped for XML, bytes that are not UTF-8 or XML characters become '?', long labels are
// shortened (the whole text stays in a tooltip). Times outside [from, to] are clipped to it; an
// empty or reversed period draws no time axis. The hour ticks fall on whole local hours of `zone`,
// so a day with a daylight-saving change shows 23 or 25 hours. Pure: no clock, no I/O.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rondo/core/task.h"
#include "rondo/core/time.h"
#include "rondo/core/timezone.h"

namespace rondo::app {

struct DayRow {
  std::string task_id{};
  std::string label{};                           // e.g. the activity
  std::optional<TimeWindow> window{};            // absent for on-demand tasks
  std::optional<std::pair<Time, Time>> planned{};  // last planned start..end
  std::optional<std::pair<Time, Time>> actual{};   // actual start (left for it) .. end
  std::string outcome{};                         // "succeeded", "failed: <reason>", "dropped: ..."
};

struct DayPicture {
  std::string title{};
  Time from{};
  Time to{};
  TimeZone zone = TimeZone::utc();
  std::vector<DayRow> rows{};
  std::vector<std::pair<Time, Time>> charging{};  // spans on the charger
};

struct DaySvgOptions {
  double pixels_per_hour = 60;
  double lane_height = 22;
  double label_width = 260;    // the column of task names, left of the axis
  double outcome_width = 260;  // the column of outcomes, right of the axis
  std::size_t max_label_chars = 38;
};

// Where instant `t` falls horizontally (SVG user units), clipped to [day.from, day.to]:
// non-decreasing in t.
double day_x(const DayPicture& day, Time t, const DaySvgOptions& options = {});

// Instants in [from, to] at which local clocks in `zone` show a whole hour, in order.
std::vector<Time> local_hour_ticks(Time from, Time to, const TimeZone& zone);

std::string render_day_svg(const DayPicture& day, const DaySvgOptions& options = {});

}  // namespace rondo::app
