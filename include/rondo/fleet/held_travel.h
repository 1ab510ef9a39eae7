// The fleet scheduler allocator's travel oracle, kept from one allocation to the next (docs/
// fleet.md, "At scale"): the building's TravelCache read over every node of the map, so that one
// oracle serves every problem and the values it has read (its exec::SlotTable) are read again
// instead of asked of the cache again. Every value is the cache's, to the bit (the table empties
// itself when the models move on): keeping it changes no answer, only the time an answer takes.
//
//   HeldTravel held;
//   problem.travel = held.get(building, now);  // location i of the problem is map node i
#pragma once

#include <cstddef>
#include <memory>

#include "rondo/core/time.h"
#include "rondo/exec/building.h"
#include "rondo/exec/map_travel.h"

namespace rondo::fleet {

class HeldTravel {
 public:
  // How long one oracle is kept: its table holds the slots it was asked for, so a new one starts
  // it afresh once a day (the memory stays that of a day's slots).
  static constexpr Duration kKeepFor = hours(24);

  // The oracle over `building`'s travel cache and every node of its map, as of `now`: the one held,
  // unless it was made for another cache or map or more than kKeepFor before `now`.
  std::shared_ptr<const exec::SchedulerTravel> get(const exec::Building& building, Time now);
  // How many oracles were made (the first one included).
  std::size_t made() const { return made_; }

 private:
  std::shared_ptr<const exec::SchedulerTravel> travel_;
  const exec::TravelCache* cache_ = nullptr;
  Time made_at_{};
  std::size_t made_ = 0;
};

}  // namespace rondo::fleet
