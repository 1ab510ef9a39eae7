// The executor's call to the scheduler: a schedule::Problem of the pending standard tasks, from
// where and when the robot is next free, solved with trySchedule (MISSION.md §3). When what was
// planned no longer fits, every task competes again and the lowest priorities give way.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "charge_planning.h"
#include "deliveries.h"
#include "rondo/core/timezone.h"
#include "rondo/exec/map_travel.h"
#include "rondo/exec/outcome.h"
#include "rondo/exec/task_book.h"
#include "rondo/map/topo_map.h"
#include "rondo/schedule/scheduler.h"
#include "rondo/schedule/try_schedule.h"
#include "rondo/traffic/bookings.h"

namespace rondo::exec {

// How long before a spec task's release its travel is priced slot by slot (a departure before that
// is priced as at that slot's start: the robot waits where it is until it is time to leave).
inline constexpr Duration kSpecLead = hours(2);

// The per-slot travel models (M_t) each planner keeps: like TravelCache's entries, those from a
// day (kTravelKeepBehind) before the slot asked for on, and never more than two days of 15-minute
// slots, so a service that runs for months holds the day it plans over, not every slot it used.
inline constexpr std::size_t kCachedSlots = 192;
// The policies each planner keeps itself: only navigation's (to its target, departing now, asked
// again after every edge); the scheduler's are TravelCache's (TravelPlanner::solve_policy).
inline constexpr std::size_t kCachedNavigationPolicies = 64;
inline plan::TravelPlannerOptions planner_options(Duration slot_width) {
  return {.slot_width = slot_width,
          .max_cached_policies = kCachedNavigationPolicies,
          .max_cached_slots = kCachedSlots,
          .keep_behind = kTravelKeepBehind};
}

// The tasks to schedule: the ones already planned first, then the new ones, then the ones offered
// again after a drop (which may be dropped again but never preempt the running task).
struct PendingTasks {
  std::vector<TaskId> ids;
  std::size_t old_count = 0;
  std::size_t first_reoffered = 0;
};

// Planned charging's view of the battery when a problem is built (ExecutorOptions::battery_planning).
struct BatteryInputs {
  BatteryEstimator estimator{};
  double level = 1;  // predicted when the robot is next free
  double reserve = 0.2;
  double margin = 2;
  double drift_per_hour = 0;  // PlanDrift
  double drift_variance_per_hour = 0;
  map::NodeIndex dock = 0;
  Duration dock_when_waiting_over = minutes(15);
};

class SpecTasks;

// A spec task's place in a problem (docs/ltl.md, "Scheduling"): location `location` stands for the
// task; the travel to it from node n departing at slot start k is seconds[k][n] (the product
// policy's expected time until the formula is satisfied, kUnreachable's seconds when it cannot be),
// interpolated between slot starts and FIFO-repaired; the travel from it is from its end node (the
// location's node). Values, so a solver on another thread reads it as it is.
struct SpecPrice {
  schedule::LocationIndex location = 0;
  Time first_slot{};
  Duration slot_width{0};
  std::vector<std::vector<double>> seconds;  // per slot start from first_slot, per map node
  // FIFO: raises each slot start's value to at least the one before less the slot width (a
  // forward pass, as TravelCache does). Call once the values are in.
  void repair_fifo();
  Duration travel(map::NodeIndex from, Time depart) const;
  Duration lower_bound(map::NodeIndex from) const;
};

// The other robots' stops this robot gives way to (traffic::Bookings; docs/traffic.md, "Planning
// around each other"), per location of a problem, as values: travel to a location ends no earlier
// than the robot may stop there for the longest stay of its tasks there.
struct StopsAhead {
  std::vector<std::vector<traffic::Stop>> at;  // per location: the stops it gives way to
  std::vector<int> capacity;                   // per location: the node's room
  std::vector<Duration> stay;                  // per location: its tasks' longest stay there
};

// Where a robot reads the others' stops: the building's bookings and its own place among them.
struct PlanAround {
  const traffic::Bookings* bookings = nullptr;
  traffic::BookingRobot robot = 0;
};

struct ScheduleInputs {
  const map::TopoMap& map;
  const TravelCache& travel;
  const TaskBook& book;
  const TimeZone& zone;
  schedule::Scheduler& scheduler;
  std::int64_t polls;  // budget of each solver call
  std::mt19937_64& rng;
  std::int64_t capacity = 0;              // 0 = unlimited
  std::vector<OnBoard> on_board{};        // when the robot is next free
  std::optional<double> risk_alpha{};     // ExecutorOptions::risk_alpha
  std::optional<BatteryInputs> battery{};  // planned charging, when on
  const SpecTasks* specs = nullptr;        // prices spec tasks (none: the book has none)
  double speed = 1.0;                      // the robot's factor on the travel cache's standard times
  PlanAround around{};                     // the others' stops (none: it plans as if alone)
};

// A scheduling problem built from the book (on the clock's thread), ready to solve anywhere: the
// request holds values only, and its travel oracle reads `in.travel` over `nodes` (location i is
// node nodes[i]); a solver on another thread sets its own oracle over the same nodes.
struct PendingProblem {
  schedule::TryScheduleRequest request;
  std::vector<map::NodeIndex> nodes;
  std::optional<double> risk_alpha{};  // the window travel's level is 1 − risk_alpha
  std::optional<ChargePlan> battery{};  // planned charging: the dock is one of `nodes`
  std::vector<SpecPrice> specs{};       // the spec tasks' locations and their travel
  double speed = 1.0;                   // ScheduleInputs::speed
  std::optional<StopsAhead> stops{};    // the others' stops it plans around (ScheduleInputs::around)
};

// The problem's travel, and its window travel under a chance constraint, over `cache` and `nodes`;
// travel to a spec task's location as `specs` price it (the window travel too: a spec task's journey
// is priced at its expected time). `speed`: the robot's factor (SchedulerTravel). `stops`: an
// arrival where others stop is moved past them (both oracles).
void set_travel(schedule::Problem& problem, const TravelCache& cache, const std::vector<map::NodeIndex>& nodes,
                std::optional<double> risk_alpha, const std::vector<SpecPrice>& specs = {}, double speed = 1.0,
                const std::optional<StopsAhead>& stops = std::nullopt);

// One reschedule between its two halves: which tasks, and their problem.
struct ScheduleCall {
  PendingTasks pending;
  PendingProblem problem;
};

// Delivery tasks carry their transfer (precedence, load, look-alike rule), `after` the tasks among
// `pending` (the others have ended or run now), and the robot its capacity and what is on board.
// Precondition: every id is a standard task of the book with a window and a start node or a spec
// (then `in.specs` is set).
// kInvalidInput when the problem is not well formed (schedule::validate's message).
Result<schedule::TryScheduleResult> schedule_pending(const ScheduleInputs& in, const PendingTasks& pending,
                                             map::NodeIndex here, Time free,
                                             std::optional<schedule::RunningTask> running);

// schedule_pending in two halves: the problem (reads the book) and its solution (reads only the
// request and the scheduler). `also` (may be null) stops each solver call early besides the poll
// budget, e.g. a wall-time budget or a stop token.
Result<PendingProblem> pending_problem(const ScheduleInputs& in, const PendingTasks& pending, map::NodeIndex here,
                                       Time free, std::optional<schedule::RunningTask> running);
schedule::TryScheduleResult solve_pending(schedule::TryScheduleRequest& request, schedule::Scheduler& scheduler,
                                          std::int64_t polls, const schedule::StopCondition* also,
                                          std::mt19937_64& rng);

// solve_pending, with charges planned when `problem.battery` is set (charge_planning.h).
PlannedAnswer solve_planned(PendingProblem& problem, schedule::Scheduler& scheduler, std::int64_t polls,
                            const schedule::StopCondition* also, std::mt19937_64& rng);

// The outcome code of a scheduler's drop.
Outcome drop_outcome(schedule::DropCause cause);

}  // namespace rondo::exec
