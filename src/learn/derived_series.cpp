#include "rondo/learn/derived_series.h"

namespace rondo::learn {

std::vector<BinarySample> presence_at_node(const std::vector<Traversal>& log, std::string_view node, Time from, Time to,
                                           Duration step) {
  std::vector<BinarySample> out;
  if (step <= Duration::zero()) return out;
  std::size_t next = 0;  // the first traversal that starts after the current sample
  for (Time t = from; t < to; t += step) {
    while (next < log.size() && log[next].start < t) ++next;
    bool present = false;
    if (next > 0) {
      const Traversal& last = log[next - 1];
      present = last.success && last.to == node && last.start + last.duration <= t;
    }
    out.push_back({t, present});
  }
  return out;
}

std::vector<BinarySample> arrivals_in_slot(const std::vector<Traversal>& log, std::string_view node, Time from, Time to,
                                           Duration step) {
  std::vector<BinarySample> out;
  if (step <= Duration::zero()) return out;
  std::size_t next = 0;  // the first traversal that starts at or after the current slot
  for (Time t = from; t < to; t += step) {
    while (next < log.size() && log[next].start < t) ++next;
    bool arrived = false;
    for (std::size_t i = next; i < log.size() && log[i].start < t + step && !arrived; ++i) {
      arrived = log[i].success && log[i].to == node;
    }
    out.push_back({t, arrived});
  }
  return out;
}

std::vector<BinarySample> edge_outcomes(const std::vector<Traversal>& log, std::string_view edge_id) {
  std::vector<BinarySample> out;
  for (const Traversal& t : log) {
    if (t.edge_id == edge_id) out.push_back({t.start, t.success});
  }
  return out;
}

}  // namespace rondo::learn
