// How long the robot's actions take in the simulator and whether they fail: per action name, a
// lognormal spread around the expected duration, a failure probability, an occasional overrun,
// and a span from the start during which the action may not be interrupted (talking to a person).
//
//   ActionModel model({.sigma = 0.2}, {{"talk", {.sigma = 0.4, .non_interruptible = minutes(2)}}});
//   ActionSample s = model.sample(Action{"talk", {}}, minutes(5), rng);
//   // s.duration ~ 5 min · lognormal, s.non_interruptible = min(2 min, s.duration)
//
// Contract: the sample depends only on the profile, `expected` and the draws from rng; the
// duration is >= 0 and non_interruptible <= duration. An expected duration of 0 gives 0.
#pragma once

#include <map>
#include <string>

#include "rondo/core/task.h"
#include "rondo/core/time.h"
#include "rondo/sim/rng.h"

namespace rondo::sim {

struct ActionProfile {
  double sigma = 0.15;               // lognormal spread; the mean duration is `expected`
  double failure_probability = 0.02;
  double overrun_probability = 0.03;
  double overrun_factor = 2.0;       // an overrunning action takes this many times longer
  Duration non_interruptible{0};     // from the start; 0 = always interruptible
  bool operator==(const ActionProfile&) const = default;
};

struct ActionSample {
  bool success = true;
  Duration duration{0};
  Duration non_interruptible{0};  // from the start, how long the robot reports interruptible=false (0 = never)
};

class ActionModel {
 public:
  ActionModel() = default;
  ActionModel(ActionProfile fallback, std::map<std::string, ActionProfile> by_name)
      : fallback_(fallback), by_name_(std::move(by_name)) {}

  // A successful action takes expected · lognormal(-sigma²/2, sigma) (· overrun_factor with
  // overrun_probability); a failed one stops after a uniform fraction in [0.1, 1] of that.
  ActionSample sample(const Action& action, Duration expected, Rng& rng) const;
  // The profile used for an action name: its own, else the fallback.
  const ActionProfile& profile(const std::string& name) const;

 private:
  ActionProfile fallback_{};
  std::map<std::string, ActionProfile> by_name_{};
};

}  // namespace rondo::sim
