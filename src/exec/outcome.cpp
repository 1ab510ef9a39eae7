#include "rondo/exec/outcome.h"

#include "name_table.h"

namespace rondo::exec {
namespace {

constexpr NameTable<Outcome, 42> kNames{{{
    {Outcome::kNone, ""},
    {Outcome::kAdded, "added"},
    {Outcome::kScheduled, "scheduled"},
    {Outcome::kEarly, "early"},
    {Outcome::kDeparted, "departed"},
    {Outcome::kArrived, "arrived"},
    {Outcome::kDone, "done"},
    {Outcome::kTooLate, "too late"},
    {Outcome::kNoRoute, "no route"},
    {Outcome::kNavigationGaveUp, "navigation gave up"},
    {Outcome::kNavigationOverrun, "navigation overrun"},
    {Outcome::kNoRouteNow, "no route now"},
    {Outcome::kActionOverrun, "action overrun"},
    {Outcome::kActionFailed, "action failed"},
    {Outcome::kPreemptedOnDemand, "preempted on demand"},
    {Outcome::kOutranked, "outranked"},
    {Outcome::kDroppedLowestPriority, "dropped lowest priority"},
    {Outcome::kDroppedForHigherPriority, "dropped for higher priority"},
    {Outcome::kOutOfReach, "out of reach"},
    {Outcome::kDoesNotFit, "does not fit"},
    {Outcome::kCancelled, "cancelled"},
    {Outcome::kCancelPending, "cancel pending"},
    {Outcome::kRobotFault, "robot fault"},
    {Outcome::kRobotReady, "robot ready"},
    {Outcome::kInterrupted, "interrupted"},
    {Outcome::kScheduleChanged, "schedule changed"},
    {Outcome::kOverrunHeld, "overrun held"},
    {Outcome::kWindowStillOpen, "window still open"},
    {Outcome::kRunsAfterCurrent, "runs after current"},
    {Outcome::kInvalidRequest, "invalid request"},
    {Outcome::kPickupFailed, "pickup failed"},
    {Outcome::kReturnPlanned, "return planned"},
    {Outcome::kNoLongerValid, "no longer valid"},
    {Outcome::kAssumptionBroken, "assumption broken"},
    {Outcome::kOpportunity, "opportunity"},
    {Outcome::kOpportunityTaken, "opportunity taken"},
    {Outcome::kOpportunityDeclined, "opportunity declined"},
    {Outcome::kObservation, "observation"},
    {Outcome::kBattery, "battery"},
    {Outcome::kConfirmed, "confirmed"},
    {Outcome::kCharging, "charging"},
    {Outcome::kSpecUnsatisfiable, "spec unsatisfiable"},
}}};

}  // namespace

std::string_view to_string(Outcome outcome) {
  return kNames.name(outcome);
}

std::optional<Outcome> parse_outcome(std::string_view name) {
  return kNames.parse(name);
}

std::span<const Outcome> all_outcomes() {
  return kNames.values;
}

}  // namespace rondo::exec
