// What the executor is configured with and what it counts: shared by the executor and its steps.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/task.h"
#include "rondo/core/time.h"
#include "rondo/exec/battery_estimator.h"
#include "rondo/map/topo_map.h"

namespace rondo::exec {

// An edge whose live success probability is below this is held to be blocked for now
// (ExecutorOptions::blocked_edge).
inline constexpr double kLikelyPassable = 0.5;
// A journey holds an edge blocked for now after two or more failures of it in a row (by any
// journey) that the live model, when each was tried, gave less than this chance together; a task's
// journey only when its task can wait until the edge is likely passable again.
inline constexpr double kRefuted = 0.01;

// The α a deployment plans with when its file does not say (`executor.risk_alpha`; null: expected
// values): chosen on validation seeds 101-110 of examples/witham and examples/g4s (docs/executor.md,
// "The window watch").
inline constexpr double kDeploymentRiskAlpha = 0.1;

struct ExecutorOptions {
  map::NodeIndex dock = 0;
  double navigation_overrun = 2.0;       // preempt navigation past this x expected travel + slack
  Duration navigation_slack = seconds(60);
  double action_overrun = 1.5;           // preempt actions past this x processing time + slack
  Duration action_slack = seconds(30);
  // An action that waits for a person (loading, unloading) is given at least this quantile of
  // that person's learned times (+ action_slack) before the monitor stops it, once a few of them
  // are known: people are sometimes slow, and a courier that gives up on them fails the delivery
  // (docs/executor.md, "Deliveries"). 0: the overrun factor alone; at most 0.98, the learned
  // quantiles' last level. 0.98 was chosen on the office example's validation seeds 101-103.
  double person_patience = 0.98;
  Duration dock_when_waiting_over = minutes(15);  // longer waits are spent on the charger
  // A fleet gives the unstarted tasks of a robot that cannot work (a fault, out of service) to its
  // other robots after this long (a fault that clears sooner keeps them).
  Duration reallocate_after = minutes(2);
  // The battery (docs/executor.md, "Battery"), states of charge in [0, 1]. Below
  // `battery_threshold` the robot goes to charge at the next interruptible moment, whatever the
  // schedule says, and starts nothing new until the battery is back at `battery_resume` (0: at
  // `battery_reserve`); 0 turns the threshold off. `battery_reserve` is the level a schedule is
  // to keep: with `battery_planning`, a schedule whose predicted state of charge falls below the
  // reserve plus `battery_margin` standard errors of the predicted drop gets a charge at the dock
  // where it costs least, or gives up what cannot be done without one (docs/executor.md,
  // "Planned charging"). Off: the robot charges when it is idle at the dock and below the threshold.
  double battery_reserve = 0.2;
  double battery_threshold = 0.1;
  double battery_resume = 0;
  bool battery_planning = false;
  double battery_margin = 2;
  // The chance constraint (docs/scheduling.md, "Slack sized by risk"): a task is planned only
  // where its departure leaves the (1 − risk_alpha)-quantile of its route's learned travel time
  // before its latest start, so it starts in its window with probability >= 1 − risk_alpha.
  // Timing and the objective stay on expected values. Nothing: plan with expected values alone
  // (the published system; a deployment file gets kDeploymentRiskAlpha unless it says null).
  std::optional<double> risk_alpha{};
  // Under the chance constraint, the navigation monitor lets a journey run to the (1 −
  // navigation_alpha)-quantile of its learned travel time + navigation_slack before it stops it
  // (when that is later than the overrun factor's limit): the share of journeys that follow the
  // learned distribution and are stopped all the same, its false alarms. Nothing: risk_alpha.
  // Without risk_alpha it does nothing (no distribution is learned).
  std::optional<double> navigation_alpha{};
  // Under the chance constraint, a journey to a task past its monitor's limit is stopped only when
  // the task can no longer be expected to start in its window: when, even if the edge in progress
  // ended now, the (1 − risk_alpha)-quantile of the way on from its end would arrive after the
  // task's latest start. Until then the monitor looks again at the last moment that would still
  // do (docs/executor.md, "The window watch"). False: stop at the limit. Without risk_alpha it
  // does nothing.
  bool navigation_window = true;
  // Travel times along the route (docs/planning.md, "Travel times along the route"): where the
  // expected travel with each edge read when the robot reaches it differs from the departure
  // slot's reading by more than this, the scheduler and the navigation monitor use the former
  // (exec::TravelCache). Nothing: the departure slot alone (the published system).
  std::optional<Duration> route_threshold{};
  int max_failed_edges = 25;                      // a navigation gives up after this many failed attempts
  // After a failed edge, when trying again is not worth it by the live model (the attempts left
  // before max_failed_edges are more likely than not all to fail, or the travel still to go would
  // take the navigation past its monitor's limit): kWait puts a task with a window back in the
  // queue, not to be scheduled before the edge is likely passable again; kGiveUp fails the task
  // at once ("no route now"); kRetry tries anyway, until the monitor or max_failed_edges stops it
  // (docs/executor.md, "A way found blocked").
  // Under kWait a task also waits before it leaves, when its way crosses an edge held to be blocked
  // (kLikelyPassable) and a later departure is expected to arrive sooner.
  enum class BlockedEdge { kRetry, kGiveUp, kWait };
  BlockedEdge blocked_edge = BlockedEdge::kWait;
  // kWait for an on-demand task (no window): it waits for the way while that is likely passable
  // again within this long of its request, and fails ("no route now") otherwise; zero: at once.
  Duration on_demand_patience = hours(4);
  std::optional<Duration> refit_at = hours(2);  // local time of day; nothing = never refit
  // The nightly refit reads the traversals that started within this long before it (nothing: the
  // whole log), so a night costs the same however long the robot has lived (docs/executor.md).
  std::optional<Duration> refit_window = hours(24 * 14);
  // The live weekly term (learn::WeeklyMemory): first attempts by time of week, beside the refit's
  // window, each count's weight halving in this long; nothing: no live weekly term.
  std::optional<Duration> weekly_half_life = hours(24 * 28);
  // Travel estimates from the online edge model (each edge updated with every attempt, on the
  // nightly snapshot); false: the snapshot alone (plan::LearnedEdgeModels::Reading).
  bool online_model = true;
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
  // Rescheduling on a worker thread (`rondo serve`; docs/executor.md, "Background scheduling"):
  // the clock's thread hands a snapshot of the problem over and keeps running the old schedule; the
  // answer is applied when still valid. Requests in between are merged into one reschedule, at most
  // one per `background_interval` of wall time, each given `background_budget` of wall time on top
  // of `scheduler_polls`. Off: every change reschedules at once, deterministically (`rondo run`).
  bool background_scheduling = false;
  // Finished tasks leave memory and stay only in the store (`rondo serve`: a service that runs for
  // months does not grow; TaskBook::forget_finished). Off: every task stays in memory, for the
  // report of `rondo run`.
  bool forget_finished = false;
  Duration background_interval = milliseconds(100);
  Duration background_budget = seconds(2);
  // At most this many tasks new to the scheduler (added, or dropped for now and offered again)
  // in one background problem, the soonest due first; the others wait for the next one (0: no
  // limit). A restore brings back every queued task as new, and thousands of them in one
  // problem outlast the budget: the drop loop then found no schedule for any subset and dropped
  // them all, the task due now with the ones for tomorrow (docs/executor.md).
  std::size_t background_offered = 64;
};

// Figures of the run so far, for the report.
struct ExecutorStats {
  int navigation_attempts = 0;
  int navigation_successes = 0;
  Duration travelling{0};  // edge attempts
  Duration acting{0};      // actions
  Duration waiting{0};     // waiting for a window to open
  Duration busy{0};        // a task in progress: its travel, waiting and actions
  int schedules = 0;       // scheduler calls
  int background_runs = 0;   // reschedules solved on the worker (background_scheduling)
  int background_stale = 0;  //   of which the answer came too late: the book had moved on
  std::size_t background_travel_policies = 0;  // held by the worker's travel cache, at its last answer
};

// A journey's wait for the way another robot holds (docs/traffic.md): where, behind whom, and how
// it ended: "passed" (granted), "made way" (sent aside), "stopped" (the journey ended waiting).
struct TrafficWait {
  std::string robot{};
  std::string node{};                 // where it waited
  std::vector<std::string> behind{};  // the robots holding its way when it began to wait
  Time start{};
  std::optional<Time> end{};
  std::string how{};
};

// Setting out later for another robot's stop at a task's place (docs/traffic.md): when, and
// whose stop ("r1 stops at Kitchen until about 08:10").
struct PutOff {
  Time depart{};
  std::string behind{};
};

// Departures a robot put off so as to arrive after another robot's stop at its task's place
// (planning around each other, docs/traffic.md): how many, and by how much in all.
struct TrafficDeferrals {
  std::size_t count = 0;
  Duration total{0};
};

// The battery as the executor saw it (BatteryWatch): readings, the lowest, stays on the charger,
// and what it learned of the battery's costs.
struct BatteryFigures {
  std::size_t readings = 0;
  double lowest = 1;              // the lowest state of charge read
  std::optional<Time> lowest_at{};
  int charges = 0;                // stays on the charger
  Duration on_charger{0};         // their total length
  int low_battery = 0;            // times the battery fell below the hard threshold
  std::size_t empty_readings = 0;  // readings of an empty battery (the robot ran flat)
  BatteryRates learned{};         // BatteryEstimator::rates()
  BatteryRates standard_errors{};
  std::size_t intervals_learned = 0;
};

// One navigation of a task to its start: what the executor expected when it left, and what
// happened. The travel-estimate error of a run is read from these.
struct NavigationRecord {
  TaskId task;
  Time start{};
  Duration expected{0};          // the estimate the executor used (online model, when it is on)
  Duration offline_expected{0};  // what the nightly snapshot alone said for the same journey
  Duration actual{0};
  bool arrived = false;
};

// A loading or unloading time learned at a place (the person there).
struct LearnedActionTime {
  std::string action;
  std::string place;
  double expected_seconds = 0;
  std::size_t samples = 0;
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
