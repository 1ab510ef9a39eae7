#include "rondo/plan/journeys.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <string_view>
#include <utility>

namespace rondo::plan {
namespace {

Time end_of(const Traversal& t) {
  return t.start + t.duration;
}

const std::string& left_at(const Traversal& t) {
  return t.success ? t.to : t.from;
}

bool continues(const Traversal& a, const Traversal& b, const JourneyRule& rule) {
  const Duration gap = b.start - end_of(a);
  return gap >= -rule.tolerance && gap <= rule.max_gap && b.from == left_at(a);
}

}  // namespace

std::vector<Journey> cut_journeys(std::span<const Traversal> log, const JourneyRule& rule) {
  std::vector<std::size_t> order(log.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return log[a].start < log[b].start; });
  std::vector<Journey> out;
  // Per robot, its journey so far (an index into `out`) and that journey's last attempt: a fleet's
  // robots move at once, so an attempt continues only its own robot's journey.
  std::map<std::string_view, std::pair<std::size_t, std::size_t>> current;
  for (const std::size_t i : order) {
    const Traversal& b = log[i];
    auto [it, first] = current.try_emplace(b.robot, out.size(), i);
    if (first || !continues(log[it->second.second], b, rule)) {
      it->second.first = out.size();
      out.push_back({.attempts = {}, .start = b.start, .end = b.start, .origin = b.from, .destination = b.from});
    }
    it->second.second = i;
    Journey& j = out[it->second.first];
    j.attempts.push_back(i);
    j.end = std::max(j.end, end_of(b));
    j.destination = left_at(b);
    j.succeeded = b.success;
  }
  return out;
}

}  // namespace rondo::plan
