// Decoding of the parametric world's settings and effects (docs/simulation.md), shared by the
// parametric world and the replay world's prior.
#pragma once

#include "rondo/core/document.h"
#include "rondo/core/timezone.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/parametric_world.h"

namespace rondo::sim::detail {

// speed, failure_probability, noise, failed_duration and (with_bursts) bursts, read from `f` into
// `spec`; keys that are absent keep spec's values. Does not check for unknown keys.
Status decode_edge_settings(const Field& f, bool with_bursts, ParametricSpec& spec);
// One effect: selectors resolved on `map`, times read in `zone`.
Result<EdgeEffect> decode_effect(const Field& f, const map::TopoMap& map, const TimeZone& zone);

}  // namespace rondo::sim::detail
