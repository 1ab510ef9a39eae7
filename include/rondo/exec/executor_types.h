// What the executor is configured with and what it counts: shared by the executor and its steps.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "rondo/core/task.h"
#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"

namespace rondo::exec {

struct ExecutorOptions {
  map::NodeIndex dock = 0;
  double navigation_overrun = 2.0;       // preempt navigation past this x expected travel + slack
  Duration navigation_slack = seconds(60);
  double action_overrun = 1.5;           // preempt actions past this x processing time + slack
  Duration action_slack = seconds(30);
  Duration dock_when_waiting_over = minutes(15);  // longer waits are spent on the charger
  int max_failed_edges = 25;             // a navigation gives up after this many failed attempts
  std::optional<Duration> refit_at = hours(2);    // local time of day; nothing = never refit
  int duration_bins = 24;                // time-of-day bins of the refitted travel-time models
  Duration slot_width = minutes(15);     // travel-time slots of the planner
  std::int64_t scheduler_polls = 20'000;  // deterministic budget of each scheduler call (docs/scheduling.md)
  std::uint64_t seed = 1;                // ties in dropping
  std::string robot_name = "robot";      // the robot's row in the store's robot_state
  int capacity = 0;                      // load units the robot carries (0 = unlimited)
  // Where an object goes back to when its delivery is cancelled or fails with it on board: a node
  // name, or empty for the object's pickup place; the return must be done within `return_within`.
  std::string return_to{};
  Duration return_within = hours(4);
};

// Figures of the run so far, for the report.
struct ExecutorStats {
  int navigation_attempts = 0;
  int navigation_successes = 0;
  Duration travelling{0};  // edge attempts
  Duration acting{0};      // actions
  Duration waiting{0};     // waiting for a window to open
  Duration busy{0};        // a task in progress: its travel, waiting and actions
  int refits = 0;
  int schedules = 0;       // scheduler calls
};

// One navigation of a task to its start: what the executor expected when it left, and what
// happened. The travel-estimate error of a run is read from these.
struct NavigationRecord {
  TaskId task;
  Time start{};
  Duration expected{0};
  Duration actual{0};
  bool arrived = false;
};

// An object on board: a delivery job picked up and not yet dropped.
struct OnBoard {
  std::string job;
  std::string object;
  std::string appearance;
  int load = 1;
  TaskId picked_up_by;  // the pickup task
};

}  // namespace rondo::exec
