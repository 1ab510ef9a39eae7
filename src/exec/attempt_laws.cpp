#include "attempt_laws.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rondo::exec {

std::vector<plan::DurationPoint> group_means(std::vector<double>& ratios, std::size_t points) {
  std::vector<plan::DurationPoint> law;
  if (ratios.empty() || points == 0) return law;
  std::sort(ratios.begin(), ratios.end());
  const std::size_t groups = std::min(points, ratios.size());
  const double n = static_cast<double>(ratios.size());
  for (std::size_t g = 0; g < groups; ++g) {
    const auto begin = static_cast<std::size_t>(std::floor(n * static_cast<double>(g) / static_cast<double>(groups)));
    const auto end = static_cast<std::size_t>(std::floor(n * static_cast<double>(g + 1) / static_cast<double>(groups)));
    if (end <= begin) continue;
    double sum = 0.0;
    for (std::size_t i = begin; i < end; ++i) sum += ratios[i];
    law.push_back({sum / static_cast<double>(end - begin), static_cast<double>(end - begin) / n});
  }
  return law;
}

plan::AttemptLaws learn_attempt_laws(const learn::EdgeModels& models, std::span<const Traversal> log,
                                     std::size_t points) {
  std::vector<double> success;
  std::vector<double> failure;
  for (const Traversal& t : log) {
    const auto index = models.index_of(t.edge_id);
    if (!index) continue;
    const double expected = models.expected_seconds(*index, t.start);
    const double seconds = to_seconds(t.duration);
    if (!(expected > 0.0) || !std::isfinite(expected) || !(seconds >= 0.0) || !std::isfinite(seconds)) continue;
    (t.success ? success : failure).push_back(seconds / expected);
  }
  return {.success = group_means(success, points), .failure = group_means(failure, points)};
}

std::vector<plan::StoppedAttempts> learn_stopped_attempts(const map::TopoMap& map, std::span<const Traversal> log,
                                                          std::span<const store::Observation> stopped,
                                                          std::size_t points) {
  std::vector<std::vector<double>> seconds(map.edge_count());
  for (const store::Observation& o : stopped) {
    if (o.what != kStoppedAttempt || !std::isfinite(o.value) || !(o.value > 0.0)) continue;
    if (const auto e = map.find_edge(o.where)) seconds[*e].push_back(o.value);
  }
  std::vector<std::size_t> ended(map.edge_count(), 0);
  for (const Traversal& t : log)
    if (const auto e = map.find_edge(t.edge_id)) ++ended[*e];
  std::vector<plan::StoppedAttempts> out(map.edge_count());
  for (map::EdgeIndex e = 0; e < map.edge_count(); ++e) {
    if (seconds[e].empty()) continue;
    const auto n = static_cast<double>(seconds[e].size());
    out[e] = {.share = n / (n + static_cast<double>(ended[e])), .law = group_means(seconds[e], points)};
  }
  return out;
}

}  // namespace rondo::exec
