#include "rondo/sim/action_model.h"

#include <algorithm>

namespace rondo::sim {

const ActionProfile& ActionModel::profile(const std::string& name) const {
  const auto it = by_name_.find(name);
  return it == by_name_.end() ? fallback_ : it->second;
}

ActionSample ActionModel::sample(const Action& action, Duration expected, Rng& rng) const {
  const ActionProfile& p = profile(action.name);
  // mu = -sigma²/2 makes the mean factor 1, so `expected` stays the mean duration.
  double factor = rng.lognormal(-0.5 * p.sigma * p.sigma, p.sigma);
  if (rng.bernoulli(p.overrun_probability)) factor *= p.overrun_factor;
  ActionSample s;
  s.success = !rng.bernoulli(p.failure_probability);
  if (!s.success) factor *= rng.uniform(0.1, 1.0);
  s.duration = from_seconds(std::max(0.0, to_seconds(expected) * factor));
  s.non_interruptible = std::clamp(p.non_interruptible, Duration{0}, s.duration);
  return s;
}

}  // namespace rondo::sim
