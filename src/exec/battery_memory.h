// What the battery estimator has learned, as text for the store's meta table (docs/storage.md,
// `exec.battery.<robot>`), so that a restarted executor goes on from it instead of the prior.
// Versioned JSON: {"version": 1, "n": 412, "a": [[...] x 5], "b": [...], "yy": ..., "noise_ss": ...,
// "noise_weight": ...}, every number written so that it reads back to the same double.
//
//   store::set_meta(db, battery_meta_key("robot"), encode_battery_state(estimator.state()));
//   Result<BatteryEstimator::State> s = decode_battery_state(text);   // kInvalidInput, saying why
#pragma once

#include <string>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/exec/battery_estimator.h"

namespace rondo::exec {

inline constexpr int kBatteryStateVersion = 1;

// The meta key of a robot's battery estimate.
std::string battery_meta_key(std::string_view robot);

std::string encode_battery_state(const BatteryEstimator::State& state);
// A stored value back: kInvalidInput naming what is wrong (not JSON, another version, a field
// missing or of the wrong shape). Whether the numbers make an estimator is BatteryEstimator::restore's.
Result<BatteryEstimator::State> decode_battery_state(std::string_view text);

}  // namespace rondo::exec
