// Which robot does each task (issue 38, "Every task belongs to at most one robot at a time"). The
// fleet asks its allocator when tasks come in; the allocator answers from each robot's current
// schedule, and the robot then schedules what it was given with the rest of its own work. The fleet
// scheduler (schedule::FleetScheduler, issue 39) implements this interface too.
//
//   GreedyAllocator greedy;
//   std::vector<Allocation> to = greedy.allocate(units, robots, building);  // one per unit
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "rondo/core/task.h"
#include "rondo/exec/building.h"
#include "rondo/exec/executor.h"

namespace rondo::fleet {

// Tasks that go to one robot together: one task, or both halves of a delivery job (the object
// stays on the robot that picked it up).
struct AllocationUnit {
  std::vector<const Task*> tasks;     // in the order given
  std::vector<std::size_t> eligible;  // the robots that may take it (indices into the fleet's robots); never empty
};

// A unit's robot, and what the allocator knows of the choice.
struct Allocation {
  std::size_t robot = 0;  // an index into the fleet's robots, one of the unit's `eligible`
  // The unit fits the robot's current schedule as the allocator sees it. When it fits none, the
  // robot's own scheduler decides (and may drop it for now); the fleet does not move a task dropped
  // for now to a robot where it would not fit either.
  bool fits = false;
  std::string why;  // why this robot over the others, for the event log and the API
};

// Whether `robot` can take on the unit's pickups beside what it carries now: no object on board
// looks like one of them, and the loads fit its capacity.
bool room_on_board(const AllocationUnit& unit, const exec::Executor& robot);

class Allocator {
 public:
  virtual ~Allocator() = default;
  // One allocation per unit, in order. Units are allocated in order: a unit's choice sees the units
  // before it on their robots.
  virtual std::vector<Allocation> allocate(const std::vector<AllocationUnit>& units,
                                           const std::vector<const exec::Executor*>& robots,
                                           const exec::Building& building) = 0;
};

// Cheapest insertion (Solomon's I1 family, without its time-window urgency term): each unit goes
// to the robot whose current schedule it lengthens least in expected travel time, where every task
// of that schedule still starts in its window; when it fits no robot's schedule, to the robot where
// it would start soonest (that robot's scheduler may then drop it for now). An on-demand task goes
// to the free robot that can reach it soonest; when none is free, to the robot whose running task it
// may interrupt, the lowest-priority task first (then the soonest there); when none can be
// interrupted, to the robot that can be there soonest after its work. Ties: the robot listed first.
// It is the baseline the fleet scheduler is measured against.
class GreedyAllocator final : public Allocator {
 public:
  std::vector<Allocation> allocate(const std::vector<AllocationUnit>& units,
                                   const std::vector<const exec::Executor*>& robots,
                                   const exec::Building& building) override;
};

}  // namespace rondo::fleet
