// How fast each robot of a fleet crosses the building, against the others (issue 38, "Learning
// from the whole fleet"): a factor per robot, so that one set of edge models serves every robot
// and a slow robot's times do not bias a fast one's estimates.
//
//   RobotSpeeds speeds = RobotSpeeds::fit(log);                 // every robot's traversals
//   auto fitted = EdgeModels::fit(specs, speeds.standardised(log));  // the fleet's standard robot
//   Duration mine = speeds.own_time("r3", standard_estimate);    // r3's time on the way
//
// The model (docs/learning.md, "A speed factor per robot"). The successful attempts with a
// duration, y = log(seconds), are y = a_e + b_r + noise: a_e per edge, b_r per robot. The fit is
// the least-squares one with a ridge of `prior_attempts` (4) on each b_r (a robot with few attempts
// stays near the fleet's pace; an edge only one robot crosses tells nothing of it), by
// alternating exact updates of a and b (block coordinate descent, converging to the unique
// minimum). b is then centred on the attempt-weighted mean, so the fleet's standard robot is its
// attempt-weighted geometric-mean pace and a lone robot's factor is exactly 1. factor_r =
// exp(−b_r), clamped to [min_factor, max_factor]: a robot of factor 0.8 takes 1 / 0.8 of the
// standard time, as a simulated robot of `speed: 0.8` does.
// The factors are fitted on successful attempts; standardised() scales every attempt of a robot (a
// slow robot's failures take longer too). Imported attempts (no robot) keep the factor 1.
#pragma once

#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/core/traversal.h"

namespace rondo::learn {

struct RobotSpeedOptions {
  // The ridge on each robot's log-pace, in pseudo-attempts at the fleet's pace: σ²/τ² for an
  // attempt's log-time noise σ ≈ 0.4 (doors, crowds, retries) and robots' paces spread τ ≈ 0.2.
  double prior_attempts = 4;
  int max_sweeps = 200;     // alternating updates at most (stops earlier at `tolerance`)
  double tolerance = 1e-9;  // largest change of any b_r in a sweep
  double min_factor = 0.25;
  double max_factor = 4.0;
};

class RobotSpeeds {
 public:
  // Every robot is at the fleet's pace (factor 1).
  RobotSpeeds() = default;
  // Precondition: every factor > 0 and finite.
  explicit RobotSpeeds(std::map<std::string, double, std::less<>> factors) : factors_(std::move(factors)) {}

  static RobotSpeeds fit(std::span<const Traversal> log, const RobotSpeedOptions& options = {});

  // 1 for a robot the fit did not see.
  double factor(std::string_view robot) const;
  const std::map<std::string, double, std::less<>>& factors() const { return factors_; }
  // The log as the standard robot would have made it: every attempt's duration × its robot's factor.
  std::vector<Traversal> standardised(std::span<const Traversal> log) const;
  Traversal standardised(Traversal attempt) const;
  // An attempt of `robot` in standard seconds, and a standard time as `robot`'s.
  double standard_seconds(std::string_view robot, double seconds) const { return seconds * factor(robot); }
  Duration own_time(std::string_view robot, Duration standard) const;

  bool operator==(const RobotSpeeds&) const = default;

 private:
  std::map<std::string, double, std::less<>> factors_;
};

}  // namespace rondo::learn
