// What `rondo run` reports: report.json (tasks by final state and reason, navigation, distance,
// time use, the Table I of the run's own travel estimates) and the per-day schedule pictures.
#pragma once

#include <chrono>
#include <map>
#include <span>
#include <string>

#include "day_svg.h"
#include "deployment.h"
#include "rondo/core/document.h"
#include "rondo/core/timezone.h"
#include "rondo/core/traversal.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/map/topo_map.h"
#include "rondo/store/events.h"

namespace rondo::app {

struct RunFigures {
  Time from{};
  Time to{};
  // From the traversal log, so that they cover a resumed run from its start.
  int navigation_attempts = 0;
  int navigation_successes = 0;
  double distance_m = 0;
  Duration charging{0};
  // Per robot, by name: the distance from the traversal log, the time on the charger.
  std::map<std::string, double> distance_by_robot{};
  std::map<std::string, Duration> charging_by_robot{};
};

// The "tasks" object: added, completed, pending, and failed/dropped/cancelled/preempted by reason.
Json task_summary(const fleet::Fleet& fleet);

// Table I on the run's own log: models trained on no data, week 1 and weeks 1–2, scored on the
// journeys of week 3 (a run of 14–20 days: no data and week 1, scored on week 2). A "note" in
// place of the table when the run is shorter than 14 days. Time of day is local time in `zone`.
Json travel_table(const map::TopoMap& map, std::span<const Traversal> log, Time start, int days,
                  const TimeZone& zone);

// The estimates the executor used (NavigationRecord::expected) and the snapshot's alone, scored
// on the same journeys (those that arrived) in Table I's columns, with each estimate's sum over the
// sum of the actual times ("sum_ratio": 1 right on the whole, above 1 over-estimating);
// report.json's "live_estimates".
Json live_estimates(std::span<const exec::NavigationRecord> navigations);

// Per 7-day block from `from` (the last may be shorter): edge attempts, failed ones, the edge that
// failed most, and tasks failed on navigation by code (navigation overrun, navigation gave up, no
// route, no route now), from the traversal log and the event log, so a reader can see learning
// happen (or not) week by week; report.json's "weeks".
Json weekly_summary(std::span<const Traversal> log, std::span<const store::Event> events, Time from, Time to);

// report.json's "battery": lowest state of charge, stays on the charger, falls below the hard
// threshold, tasks moved/dropped/failed for charging by event, and the learned costs. For a fleet of
// several robots: the counts summed, the lowest of all, and the learned costs per robot only.
Json battery_summary(const fleet::Fleet& fleet);

// report.json's "robots": per robot, its tasks by final state, distance, time use and battery.
Json robot_summaries(const fleet::Fleet& fleet, const RunFigures& figures);

// Every key is the fleet's total (a fleet of one: its robot's), with "robots" per robot.
Json run_report(const fleet::Fleet& fleet, const RunFigures& figures);

// report.json's "reference": the real deployment's figures (`reference:`) and the run's beside
// them, both also per day, since the run may be shorter or longer. `report` is the rest of the
// report (its "tasks" and "navigation").
Json reference_figures(const ReferenceFigures& reference, const Json& report, int days);

// The schedule picture of one local day [from, to): the tasks allocated to `executor`'s robot
// (every task when `every_task`).
DayPicture day_picture(const exec::Executor& executor, const std::string& title, Time from, Time to,
                       const TimeZone& zone, bool every_task = false);

}  // namespace rondo::app
