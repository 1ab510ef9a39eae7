// Journeys: a traversal log cut into the trips the robot made, each a chain of edge attempts from
// an origin to a destination, retries included. What travel-time estimates are scored against.
//
//   std::vector<Journey> js = cut_journeys(log);               // log in any order
//   for (const Journey& j : js) if (j.succeeded) use(j.seconds(), j.origin, j.destination);
//
// The rule (docs/planning.md). Sort the attempts by start time (ties keep log order). An attempt
// b continues the journey of the attempt a just before it of the same robot (Traversal::robot; a
// fleet's robots feed one log, and move at once) when both hold:
//   - b starts within [-tolerance, max_gap] of a's end (a.start + a.duration); the tolerance covers
//     start times logged in whole seconds;
//   - b starts where a left the robot: a's `to` after a success, a's `from` after a failure (the
//     MDP's "a failed attempt leaves the robot where it was").
// Otherwise b starts a new journey. So a journey is a maximal such chain. It succeeded when its
// last attempt did; its ground-truth duration is last end − first start (gaps and retries in).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/core/traversal.h"

namespace rondo::plan {

struct JourneyRule {
  Duration max_gap = seconds(5);    // longest pause between one attempt's end and the next start
  Duration tolerance = seconds(1);  // how far the next start may fall before the end
};

struct Journey {
  std::vector<std::size_t> attempts;  // indices into the log, in the order they were made
  Time start{};                       // of the first attempt
  Time end{};                         // of the last attempt: its start + duration
  std::string origin;                 // `from` of the first attempt
  std::string destination;            // where the last attempt left the robot
  bool succeeded = false;             // the last attempt succeeded

  double seconds() const { return to_seconds(end - start); }
};

// Journeys in order of their start. Every attempt belongs to exactly one journey.
std::vector<Journey> cut_journeys(std::span<const Traversal> log, const JourneyRule& rule = {});

}  // namespace rondo::plan
