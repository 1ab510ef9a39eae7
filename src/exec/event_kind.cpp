#include "rondo/exec/event_kind.h"

#include "name_table.h"

namespace rondo::exec {
namespace {

constexpr NameTable<EventKind, 45> kNames{{{
    {EventKind::kScheduled, "scheduled"},
    {EventKind::kReOffered, "re-offered"},
    {EventKind::kDroppedForNow, "dropped for now"},
    {EventKind::kRetryPlanned, "retry planned"},
    {EventKind::kWaitsForRunningTask, "waits for the running task"},
    {EventKind::kWaitsForTheCharge, "waits for the charge"},
    {EventKind::kOverrun, "overrun"},
    {EventKind::kInterrupted, "interrupted"},
    {EventKind::kCancelPending, "cancel pending"},
    {EventKind::kNotHalted, "not halted"},
    {EventKind::kChanged, "changed"},
    {EventKind::kConfirmed, "confirmed"},
    {EventKind::kBlocked, "blocked"},
    {EventKind::kOpportunity, "opportunity"},
    {EventKind::kOpportunityDeclined, "opportunity declined"},
    {EventKind::kStaysOnBoard, "stays on board"},
    {EventKind::kReturnPlanned, "return planned"},
    {EventKind::kEdge, "edge"},
    {EventKind::kAllocated, "allocated"},
    {EventKind::kReallocated, "re-allocated"},
    {EventKind::kDeparted, "departed"},
    {EventKind::kArrived, "arrived"},
    {EventKind::kWaits, "waits"},
    {EventKind::kGaveUp, "gave up"},
    {EventKind::kTrafficWait, "traffic wait"},
    {EventKind::kMadeWay, "made way"},
    {EventKind::kWaitsLonger, "waits longer"},
    {EventKind::kStopped, "stopped"},
    {EventKind::kFault, "fault"},
    {EventKind::kReady, "ready"},
    {EventKind::kBatteryLow, "battery low"},
    {EventKind::kCharging, "charging"},
    {EventKind::kCharged, "charged"},
    {EventKind::kChargeMissed, "charge missed"},
    {EventKind::kWayHomeClosed, "way home closed"},
    {EventKind::kBatteryEstimateReset, "battery estimate reset"},
    {EventKind::kOutOfService, "out of service"},
    {EventKind::kBackInService, "back in service"},
    {EventKind::kAssumptions, "assumptions"},
    {EventKind::kRescheduled, "rescheduled"},
    {EventKind::kNotRescheduled, "not rescheduled"},
    {EventKind::kLookAlike, "look-alike"},
    {EventKind::kChargePlanned, "charge planned"},
    {EventKind::kRejected, "rejected"},
    {EventKind::kRoutinesAdded, "routines added"},
}}};

}  // namespace

std::string_view to_string(EventKind kind) {
  return kNames.name(kind);
}

std::optional<EventKind> parse_event_kind(std::string_view name) {
  return kNames.parse(name);
}

std::span<const EventKind> all_event_kinds() {
  return kNames.values;
}

}  // namespace rondo::exec
