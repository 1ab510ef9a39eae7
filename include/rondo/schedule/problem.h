// The scheduling problem of one robot (MISSION.md §2, §5): tasks with release dates, deadlines,
// processing times, priorities and start/end locations; the robot's position, time, capacity and
// items on board; a travel oracle. Independent of rondo::Task: an adapter builds a Problem.
//
//   Problem p;
//   p.travel = std::make_shared<MatrixTravel>(*MatrixTravel::create(2, {0ms, 60s, 60s, 0ms}));
//   p.robot = {.location = 0, .time = t0};
//   p.tasks.push_back({.id = "check-door", .release = t0, .deadline = t0 + minutes(30),
//                      .duration = minutes(2), .start_location = 1, .end_location = 1});
//   if (auto ok = validate(p); !ok) ...;
//
// The objective of every solver is the sum of the tasks' end times, measured from robot.time.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/schedule/travel_oracle.h"

namespace rondo::schedule {

// Which instant the deadline bounds. The robot executive's tasks bound the end (e <= d); TSPTW
// customers bound the start (s <= d). Both are exact: latest_start() converts.
enum class DeadlineOn { kEnd, kStart };

enum class ItemAction { kPickup, kDrop };

// One half of a delivery job (MISSION.md §5). A drop needs its pickup earlier in the schedule, or
// the item on board at the start. Items that share an appearance are never on board together.
struct ItemTransfer {
  std::string job{};
  ItemAction action = ItemAction::kPickup;
  std::string appearance{};  // "" = looks like nothing else
  std::int64_t load = 1;   // capacity units
};

struct ProblemTask {
  std::string id{};
  Time release{};   // earliest start
  Time deadline{};  // latest end, or latest start when deadline_on == kStart
  DeadlineOn deadline_on = DeadlineOn::kEnd;
  Duration duration{0};
  int priority = 0;  // higher = more important (used by try_schedule, not by the objective)
  LocationIndex start_location = 0;
  LocationIndex end_location = 0;
  std::optional<ItemTransfer> transfer{};
  std::vector<std::size_t> after{};  // indices of tasks that must end before this one starts

  Time latest_start() const { return deadline_on == DeadlineOn::kStart ? deadline : deadline - duration; }
};

struct OnBoardItem {
  std::string job{};
  std::string appearance{};
  std::int64_t load = 1;
};

struct RobotState {
  LocationIndex location = 0;
  Time time{};
  std::int64_t capacity = 0;  // 0 = unlimited
  std::vector<OnBoardItem> on_board{};
};

// The robot must reach `location` by `deadline` after its last task (TSPTW's depot return).
struct ReturnTo {
  LocationIndex location = 0;
  Time deadline{};
};

struct Problem {
  RobotState robot{};
  std::vector<ProblemTask> tasks{};
  std::shared_ptr<const TravelOracle> travel{};
  // The chance constraint (docs/scheduling.md, "Slack sized by risk"). When set, a task may only
  // be planned where its departure leaves this much travel before its latest start: the
  // (1 − α)-quantile of the route's travel time at that departure, so that the task starts in its
  // window with probability at least 1 − α. Timing and the objective stay on `travel` (expected
  // values). Same locations and the same contract as `travel` (FIFO in the departure time).
  std::shared_ptr<const TravelOracle> window_travel{};
  std::optional<ReturnTo> return_to{};
  std::vector<std::string> location_names{};  // optional, for messages; index = LocationIndex

  bool has_item_constraints() const;  // any transfer, capacity or item on board
  bool has_precedence() const;        // any `after`
  // The latest a task leaving `from` at `depart` for `to` arrives, as the window check counts it:
  // depart + max(travel, window_travel) (just travel without a chance constraint).
  Time window_arrival(LocationIndex from, LocationIndex to, Time depart) const;
  std::string location_name(LocationIndex l) const;
};

// Structural checks: a travel oracle, locations in range, durations >= 0, windows not empty
// (release <= latest start), `after` indices valid and acyclic, every drop has exactly one
// pickup or item on board, no job picked up twice. Names the task in the message.
Status validate(const Problem& problem);

}  // namespace rondo::schedule
