// report.json's `traffic` section (docs/simulation.md, "Traffic"): the meetings of a building's
// simulated robots, for a run with several of them.
//
//   if (parts.traffic) report["traffic"] = traffic_report(*parts.traffic);
#pragma once

#include <cstddef>

#include <vector>
#include "rondo/core/document.h"

#include "rondo/exec/executor_types.h"
#include "rondo/sim/traffic.h"
#include "rondo/traffic/reservations.h"

namespace rondo::app {

// The hold-ups listed and the collisions listed in full, the first ones of the run.
inline constexpr std::size_t kTrafficListed = 5;

// {"hold_timeout_s", "hold_ups": {count, total_s, longest_s, passed, timed_out, stopped, first},
//  "collisions": {count, at_nodes, on_narrow_edges, first}}; times in UTC.
Json traffic_report(const sim::Traffic& traffic);

// The reservations' side (docs/traffic.md): {"lookahead", "waits": {count, total_s, longest_s,
// over_2_min, passed, made_way, stopped, robots: {name: {count, total_s}}, busiest_nodes:
// [{node, waits, total_s}]}, "resolutions": {deadlocks, parked, unresolved, first}}. A wait still
// running is counted to `end`.
Json reservation_report(const traffic::Reservations& reservations, const std::vector<exec::TrafficWait>& waits,
                        Time end);

// Planning around each other (docs/traffic.md): {"departures_put_off", "put_off_s"}, the
// departures moved so as to arrive after another robot's stop, and by how much in all.
Json plan_around_report(const exec::TrafficDeferrals& deferrals);

}  // namespace rondo::app
