#include "rondo/plan/distance_prior.h"

namespace rondo::plan {

DistancePrior::DistancePrior(const map::TopoMap& map, const DistancePriorOptions& options) {
  outcomes_.reserve(map.edge_count());
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) {
    outcomes_.push_back({.success_probability = options.success_probability,
                         .expected_seconds = to_seconds(map::nominal_travel_time(map, e, options.travel))});
  }
}

EdgeCrossing DistancePrior::outcome(map::EdgeIndex edge, Time) const {
  return outcomes_.at(edge);
}

}  // namespace rondo::plan
