#include "loading_times.h"

#include <algorithm>

namespace rondo::exec {

bool LoadingTimes::learns(const std::string& action) const {
  return std::find(actions_.begin(), actions_.end(), action) != actions_.end();
}

learn::OnlineStaticDuration& LoadingTimes::model(const std::string& action, const std::string& place,
                                                 Duration declared) {
  auto it = models_.find({action, place});
  if (it == models_.end())
    it = models_.emplace(std::pair{action, place}, learn::OnlineStaticDuration(to_seconds(declared), kPriorCount))
             .first;
  return it->second;
}

void LoadingTimes::observe(const std::string& action, const std::string& place, Duration declared, Duration took,
                           bool success, Time at) {
  if (learns(action)) model(action, place, declared).observe(at, to_seconds(took), success);
}

void LoadingTimes::observe_stopped(const std::string& action, const std::string& place, Duration declared,
                                   Duration took, Time at) {
  if (learns(action)) model(action, place, declared).observe_stopped(at, to_seconds(took));
}

Duration LoadingTimes::expected(const std::string& action, const std::string& place, Duration declared) const {
  const auto it = models_.find({action, place});
  if (it == models_.end() || it->second.samples() == 0) return declared;
  return from_seconds(it->second.expected_seconds(Time{}));
}

std::vector<LearnedActionTime> LoadingTimes::entries() const {
  std::vector<LearnedActionTime> out;
  for (const auto& [key, model] : models_)
    out.push_back({.action = key.first, .place = key.second, .expected_seconds = model.expected_seconds(Time{}),
                   .samples = model.samples()});
  return out;
}

}  // namespace rondo::exec
