#include "door_models.h"

#include <algorithm>

namespace rondo::exec {

void DoorModels::observe(const std::string& door, Time when, bool open) {
  std::vector<learn::BinarySample>& s = samples_[door];
  if (!s.empty() && when - s.back().time < kSameLook && s.back().value == open) return;
  s.push_back({.time = when, .value = open});
}

bool DoorModels::observe_failed_edge(const std::string& door, Time when) {
  std::vector<learn::BinarySample>& s = samples_[door];
  if (!s.empty() && when - s.back().time < kSameLook) return false;
  double& credit = failed_edge_credit_[door];
  credit += kFailedEdgeWeight;
  if (credit < 1 - 1e-9) return false;
  credit -= 1;
  s.push_back({.time = when, .value = false});
  return true;
}

void DoorModels::refit(Time now, std::optional<Duration> window) {
  learn::EpisodeOptions options;
  options.zone = zone_;
  // Buildings keep weekly hours (offices shut at weekends): the time-of-week term always, with a
  // weak pull towards the time of day. Doors shut for an hour (a lunch, a meeting): one-hour bins
  // (averaged over four shifts of their edges), not the edges' two to twenty-four hours.
  options.weekly = learn::WeeklyTerm::kOn;
  options.weekly_prior = 2;
  options.day_resolutions = {24};
  for (auto& [door, s] : samples_) {
    if (window) std::erase_if(s, [&](const learn::BinarySample& x) { return x.time < now - *window; });
    if (s.empty()) {
      models_.erase(door);
      continue;
    }
    models_[door] = learn::fit_episode_binary(s, options);
  }
}

std::optional<double> DoorModels::probability(const std::string& door, Time t) const {
  const auto it = models_.find(door);
  if (it == models_.end() || !it->second) return std::nullopt;
  return it->second->probability(t);
}

std::optional<Time> DoorModels::next_likely_open(const std::string& door, Time from, Time until,
                                                 double threshold) const {
  if (!probability(door, from)) return std::nullopt;
  // The grid of the local day: 00:00, 00:15, ...
  const Time midnight = zone_.at(zone_.local_date(from), Duration{0});
  Time t = midnight + ((from - midnight) / kStep + 1) * kStep;
  for (; t <= until; t += kStep)
    if (*probability(door, t) >= threshold) return t;
  return std::nullopt;
}

std::size_t DoorModels::samples(const std::string& door) const {
  const auto it = samples_.find(door);
  return it == samples_.end() ? 0 : it->second.size();
}

std::vector<std::string> DoorModels::doors() const {
  std::vector<std::string> names;
  for (const auto& [door, m] : models_) names.push_back(door);
  return names;
}

}  // namespace rondo::exec
