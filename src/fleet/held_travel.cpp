#include "rondo/fleet/held_travel.h"

#include <numeric>
#include <vector>

namespace rondo::fleet {

std::shared_ptr<const exec::SchedulerTravel> HeldTravel::get(const exec::Building& building, Time now) {
  const bool fresh = travel_ && cache_ == &building.travel && travel_->location_count() == building.map.node_count() &&
                     now < made_at_ + kKeepFor && now >= made_at_;
  if (fresh) return travel_;
  std::vector<map::NodeIndex> nodes(building.map.node_count());
  std::iota(nodes.begin(), nodes.end(), map::NodeIndex{0});
  travel_ = std::make_shared<const exec::SchedulerTravel>(building.travel, std::move(nodes));
  cache_ = &building.travel;
  made_at_ = now;
  ++made_;
  return travel_;
}

}  // namespace rondo::fleet
