// The kinds of event the executor writes that are not a change of a task's state (a change of
// state is named by its TaskState): one enum, so that a kind is named in one place and the event
// log, the report and the API read the same words (docs/executor.md has the table).
//
//   book.note(id, EventKind::kRetryPlanned, Outcome::kNoRouteNow, "...");
//   to_string(EventKind::kRetryPlanned)  // "retry planned", as stored in the event log
#pragma once

#include <optional>
#include <span>
#include <string_view>

namespace rondo::exec {

enum class EventKind {
  // a task's
  kScheduled,            // given a planned start (or a new one)
  kReOffered,            // dropped for now, offered to the scheduler again
  kDroppedForNow,        // did not fit; offered again while its window can be met
  kRetryPlanned,         // a way it needs is blocked, or its door closed: it is tried again later
  kWaitsForRunningTask,  // an on-demand task waits for a running task that cannot be interrupted
  kWaitsForTheCharge,    // short of battery: a charge comes first
  kOverrun,              // a monitor's limit passed, and the task goes on (held, or its window open)
  kInterrupted,          // a fault stopped it; it goes back to the queue
  kCancelPending,        // cancel asked while it cannot be interrupted
  kNotHalted,            // out of service with halt, but it cannot be interrupted now
  kChanged,              // a person changed its window or priority
  kConfirmed,            // a person confirmed its load or unload
  kBlocked,              // a door it needs was seen closed: it waits as an opportunity
  kOpportunity,          // its door was seen open: it runs now
  kOpportunityDeclined,  // its door was seen open, but taking it would break another deadline
  kStaysOnBoard,         // its drop did not happen and the object stays on board
  kReturnPlanned,        // its drop did not happen: a new task takes the object back
  kEdge,                 // an edge attempt cancelled or cut by a fault (a task's or the robot's)
  kAllocated,            // the fleet chose its robot, and says why (a fleet of more than one)
  kReallocated,          // the fleet gave it to another robot (its robot could not work, or dropped it for now)
  // the robot's
  kDeparted,              // a journey without a task left
  kArrived,               // ... and arrived
  kWaits,                 // ... waits for a way found blocked
  kGaveUp,                // ... ended without arriving
  kTrafficWait,           // a journey waits for the way another robot holds (a task's or the robot's)
  kMadeWay,               // a journey sent aside by the traffic manager (a deadlock, or parked in the way)
  kWaitsLonger,           // an early task waits on: another robot set out for its place meanwhile
  kStopped,               // ... was stopped (the schedule changed)
  kFault,                 // the robot reported a fault (or lost its connection)
  kReady,                 // the fault is over
  kBatteryLow,            // below the hard threshold: it goes to charge
  kCharging,              // on the charger
  kCharged,               // charged back to the resume level (or as planned)
  kChargeMissed,          // a planned charge that did not happen
  kWayHomeClosed,         // the way to the charger is closed
  kBatteryEstimateReset,  // the stored battery estimate could not be read: learned afresh
  kOutOfService,          // a person paused the robot's work
  kBackInService,         // ... and resumed it
  // the schedule's
  kAssumptions,     // what the new schedule assumes (doors open, edges passable)
  kRescheduled,     // a broken assumption changed the schedule
  kNotRescheduled,  // the scheduler could not be asked (its problem was malformed)
  kLookAlike,       // why look-alike jobs do not interleave
  kChargePlanned,   // the schedule holds a charge
  // a request's
  kRejected,       // a request refused at the door
  kRoutinesAdded,  // a request's routines were added
};

// The name stored in the event log, e.g. "retry planned".
std::string_view to_string(EventKind kind);
std::optional<EventKind> parse_event_kind(std::string_view name);
// Every kind, in declaration order (for tables and tests).
std::span<const EventKind> all_event_kinds();

}  // namespace rondo::exec
