#include "rondo/plan/journeys.h"

#include <algorithm>
#include <numeric>

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
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Traversal& b = log[order[k]];
    if (k == 0 || !continues(log[order[k - 1]], b, rule)) {
      out.push_back({.attempts = {}, .start = b.start, .end = b.start, .origin = b.from, .destination = b.from});
    }
    Journey& j = out.back();
    j.attempts.push_back(order[k]);
    j.end = std::max(j.end, end_of(b));
    j.destination = left_at(b);
    j.succeeded = b.success;
  }
  return out;
}

}  // namespace rondo::plan
