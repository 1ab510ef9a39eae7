// The edges of the simulated building: how long an attempt to cross an edge takes and whether it
// succeeds, at a given time. Two implementations: ParametricWorld (rhythms described in YAML) and
// ReplayWorld (drawn from real logs at the same time of week). SimRobot asks its EdgeWorld once
// per traverse().
//
//   EdgeSample s = world.sample_edge(edge, clock.now(), rng);
//   clock.schedule_after(s.duration, [=] { finish(s.success); });
//
// Contract: calls come in non-decreasing start time (a world may keep hidden per-edge state, such
// as a burst of failures, advanced with time; an earlier start is treated as the latest one seen).
// The sample depends only on the world's state, the arguments and the draws from `rng`.
#pragma once

#include <optional>

#include "rondo/core/time.h"
#include "rondo/map/topo_map.h"
#include "rondo/sim/rng.h"

namespace rondo::sim {

struct EdgeSample {
  bool success = true;
  Duration duration{0};  // >= 0: how long the attempt took, success or not
};

class EdgeWorld {
 public:
  virtual ~EdgeWorld() = default;
  virtual EdgeSample sample_edge(map::EdgeIndex edge, Time start, Rng& rng) = 0;
  // Whether the building has the edge closed at `t` (a door shut, a corridor blocked), when the
  // world knows: what a sensor sees. Draws nothing and changes nothing.
  virtual std::optional<bool> closed_at(map::EdgeIndex /*edge*/, Time /*t*/) const { return std::nullopt; }
  // The seed of what the building does by itself, apart from the robot's draws (a door's shut
  // spells): the deployment's seed, the same when a run resumes.
  virtual void set_seed(std::uint64_t /*seed*/) {}
};

}  // namespace rondo::sim
