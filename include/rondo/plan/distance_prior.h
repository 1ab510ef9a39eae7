// The no-data edge models (the paper's W0): every attempt succeeds with a configurable prior
// probability and takes the map's distance-based travel time (map_geometry.h). It ignores the
// time of day, so its version never changes.
//
//   DistancePrior prior(map);                                        // p = 1
//   DistancePrior cautious(map, {.success_probability = 0.9});
//   Mdp mdp = Mdp::build(map, prior, depart_at);
#pragma once

#include <vector>

#include "rondo/map/map_geometry.h"
#include "rondo/map/topo_map.h"
#include "rondo/plan/edge_model_view.h"

namespace rondo::plan {

struct DistancePriorOptions {
  double success_probability = 1.0;  // of every attempt on every edge, in (0, 1]
  map::TravelTimeOptions travel{};   // speed and per-action overheads of the nominal time
};

class DistancePrior final : public EdgeModelView {
 public:
  // Reads every edge's nominal travel time once; the map is not kept.
  explicit DistancePrior(const map::TopoMap& map, const DistancePriorOptions& options = {});

  // Precondition: edge < the map's edge_count().
  EdgeCrossing outcome(map::EdgeIndex edge, Time at) const override;
  std::uint64_t version() const override { return 0; }

 private:
  std::vector<EdgeCrossing> outcomes_;
};

}  // namespace rondo::plan
