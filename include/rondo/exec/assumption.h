// What a schedule rests on (MISSION.md §5): the doors of the rooms its tasks enter are open, and
// the edges of its routes are passable. The executor records them with every schedule it makes
// and checks the robot's observations against them (docs/executor.md, "Assumptions").
#pragma once

#include <string>

#include "rondo/core/task.h"
#include "rondo/core/time.h"

namespace rondo::exec {

struct Assumption {
  enum class Kind {
    kDoorOpen,      // `what` is a door of the map (Edge::door)
    kEdgePassable,  // `what` is an edge id; a failed edge is navigation's business (it re-plans)
  };
  Kind kind = Kind::kDoorOpen;
  std::string what;
  TaskId task;   // the task that needs it
  Time until{};  // the task's planned end: after it, nothing rests on it
  bool operator==(const Assumption&) const = default;
};

// What the courier's assumptions did in a run (the report's `assumptions`).
struct AssumptionStats {
  int door_observations = 0;   // "door_open" observations seen
  int broken = 0;               // door observations that broke an assumption of the plan
  int reschedules = 0;          // reschedules they caused
  int opportunities_taken = 0;  // blocked tasks run when their door was seen open
  int opportunities_declined = 0;  // seen open, but taking them would have broken a deadline
  int failed_blocked = 0;       // blocked tasks that reached their deadline still blocked
  int retries = 0;              // blocked tasks offered again when their door was likely open
};

// "door open", "edge passable".
const char* to_string(Assumption::Kind kind);

}  // namespace rondo::exec
