#include "rondo/exec/outcome.h"

#include <array>
#include <utility>

namespace rondo::exec {
namespace {

constexpr std::array<std::pair<Outcome, std::string_view>, 41> kNames{{
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
}};

constexpr std::array<Outcome, kNames.size()> kAll = [] {
  std::array<Outcome, kNames.size()> all{};
  for (std::size_t i = 0; i < kNames.size(); ++i) all[i] = kNames[i].first;
  return all;
}();

}  // namespace

std::string_view to_string(Outcome outcome) {
  for (const auto& [o, name] : kNames)
    if (o == outcome) return name;
  return "";
}

std::optional<Outcome> parse_outcome(std::string_view name) {
  for (const auto& [o, n] : kNames)
    if (n == name) return o;
  return std::nullopt;
}

std::span<const Outcome> all_outcomes() { return kAll; }

}  // namespace rondo::exec
