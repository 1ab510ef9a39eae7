// Why a task moved, or why something else happened: the typed outcome code of every event the
// executor writes (docs/executor.md has the table). The event log stores the code's name, the
// report groups by it, and people read the event's reason text next to it.
//
//   transition(id, TaskState::kFailed, Outcome::kNavigationOverrun, "still travelling after 4 min ...");
//   to_string(Outcome::kNavigationOverrun)  // "navigation overrun"
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace rondo::exec {

enum class Outcome {
  kNone,                      // "": an event without a cause of its own
  kAdded,                     // accepted into the book
  kScheduled,                 // given a planned start (or a new one)
  kEarly,                     // waits for its window to open
  kDeparted,                  // left for the task's place
  kArrived,                   // at the place: acting
  kDone,                      // every action finished
  kTooLate,                   // cannot start in time any more (before leaving, or at a reschedule)
  kNoRoute,                   // no way to the place now (every way closed)
  kNavigationGaveUp,          // too many failed edge attempts
  kNavigationOverrun,         // the navigation monitor: far past the expected travel time
  kNoRouteNow,                // an edge failed and trying it again would take past the navigation's limit
  kActionOverrun,             // the action monitor: far past the processing time
  kActionFailed,              // the robot reported an action failed
  kPreemptedOnDemand,         // an on-demand task took the robot
  kOutranked,                 // higher-priority new tasks took its place
  kDroppedLowestPriority,     // did not fit; the lowest priority of those that did not
  kDroppedForHigherPriority,  // did not fit beside higher-priority tasks
  kOutOfReach,                // cannot be reached in its window from where the robot is
  kDoesNotFit,                // the tasks already accepted leave no room for it
  kCancelled,                 // cancelled by a person or system
  kCancelPending,             // cancel asked while not interruptible: done at the next chance
  kRobotFault,                // the robot reported a fault (or lost its connection)
  kRobotReady,                // the fault is over
  kInterrupted,               // the executive stopped while the task ran (a crash, a restart)
  kScheduleChanged,           // waiting ended because the schedule changed
  kOverrunHeld,               // a monitor fired while the task could not be interrupted
  kWindowStillOpen,           // the navigation monitor's limit passed, but the task can still start in its window
  kRunsAfterCurrent,          // an on-demand task waits for a task that cannot be interrupted
  kInvalidRequest,            // a request refused at the door
  kPickupFailed,              // a drop that cannot happen: its pickup ended without the object
  kReturnPlanned,             // a drop that did not happen: a new task takes the object back
  kNoLongerValid,             // a stored task that the changed deployment cannot run (restore)
  kAssumptionBroken,          // an observation broke what the schedule assumed (a door seen closed)
  kOpportunity,               // blocked: waits for its enabling condition while its deadline allows
  kOpportunityTaken,          // its condition was seen: it runs now (the running task interrupted)
  kOpportunityDeclined,       // its condition was seen, but taking it would break another deadline
  kObservation,               // the robot saw something that matters
  kBattery,                   // a battery reading
  kConfirmed,                 // a person confirmed a load or unload (through the API)
  kCharging,                  // the battery fell below the hard threshold: the robot charges, and a
                              // task was preempted, dropped or failed for it (or it is charged again)
  kSpecUnsatisfiable,         // a spec task's formula cannot be satisfied (the reason names the blocking nodes)
};

// The readable name, e.g. "navigation overrun"; "" for kNone.
std::string_view to_string(Outcome outcome);
std::optional<Outcome> parse_outcome(std::string_view name);
// Every code, in declaration order (for tables and tests).
std::span<const Outcome> all_outcomes();

}  // namespace rondo::exec
