// report.json's `traffic` section (docs/simulation.md, "Traffic"): the meetings of a building's
// simulated robots, for a run with several of them.
//
//   if (parts.traffic) report["traffic"] = traffic_report(*parts.traffic);
#pragma once

#include <cstddef>

#include "rondo/core/document.h"
#include "rondo/sim/traffic.h"

namespace rondo::app {

// The hold-ups listed and the collisions listed in full, the first ones of the run.
inline constexpr std::size_t kTrafficListed = 5;

// {"hold_timeout_s", "hold_ups": {count, total_s, longest_s, passed, timed_out, stopped, first},
//  "collisions": {count, at_nodes, on_narrow_edges, first}}; times in UTC.
Json traffic_report(const sim::Traffic& traffic);

}  // namespace rondo::app
