// Binary time series derived from a traversal log, for testing binary models on facts other than
// edge success: where the robot was (is it docked at its charger?) and how one edge fared.
//
//   auto docked = presence_at_node(log, "ChargingPoint", start, end, minutes(10));
//   auto door = edge_outcomes(log, "LabDoor1_LabDoor2");   // (start, success) of every attempt
//   auto kitchen = arrivals_in_slot(log, "Kitchen", start, end, hours(1));  // visited this hour?
#pragma once

#include <string_view>
#include <vector>

#include "rondo/core/traversal.h"
#include "rondo/learn/temporal_model.h"

namespace rondo::learn {

// Sampled every `step` in [from, to): true when the robot is at `node`, i.e. the latest traversal
// started before the sample succeeded, ended at `node`, and had ended by the sample time. Before
// the first traversal the state is false. `log` in start order; `step` > 0.
std::vector<BinarySample> presence_at_node(const std::vector<Traversal>& log, std::string_view node, Time from, Time to,
                                           Duration step);

// Sampled every `step` in [from, to), at the start of each slot [t, t + step): true when a
// successful traversal into `node` starts in the slot (the robot went there in that hour). `log`
// in start order; `step` > 0.
std::vector<BinarySample> arrivals_in_slot(const std::vector<Traversal>& log, std::string_view node, Time from, Time to,
                                           Duration step);

// The outcome of every attempt on one edge, at its start time.
std::vector<BinarySample> edge_outcomes(const std::vector<Traversal>& log, std::string_view edge_id);

}  // namespace rondo::learn
