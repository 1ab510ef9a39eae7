#include "rondo/schedule/problem.h"

#include <algorithm>
#include <map>

#include <fmt/format.h>

namespace rondo::schedule {

bool Problem::has_item_constraints() const {
  if (robot.capacity > 0 || !robot.on_board.empty()) return true;
  for (const auto& t : tasks)
    if (t.transfer) return true;
  return false;
}

bool Problem::has_precedence() const {
  for (const auto& t : tasks)
    if (!t.after.empty()) return true;
  return false;
}

std::string Problem::location_name(LocationIndex l) const {
  if (l < location_names.size()) return location_names[l];
  return fmt::format("location {}", l);
}

namespace {

Status check_acyclic(const Problem& p) {
  // Kahn's algorithm over `after` edges.
  const std::size_t n = p.tasks.size();
  std::vector<std::size_t> indegree(n, 0);
  std::vector<std::vector<std::size_t>> next(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t a : p.tasks[i].after) {
      ++indegree[i];
      next[a].push_back(i);
    }
  std::vector<std::size_t> ready;
  for (std::size_t i = 0; i < n; ++i)
    if (indegree[i] == 0) ready.push_back(i);
  std::size_t seen = 0;
  while (!ready.empty()) {
    const std::size_t i = ready.back();
    ready.pop_back();
    ++seen;
    for (std::size_t j : next[i])
      if (--indegree[j] == 0) ready.push_back(j);
  }
  if (seen != n) {
    for (std::size_t i = 0; i < n; ++i)
      if (indegree[i] > 0)
        return Error::invalid(fmt::format("task '{}': its `after` precedences form a cycle", p.tasks[i].id));
  }
  return {};
}

}  // namespace

Time Problem::window_arrival(LocationIndex from, LocationIndex to, Time depart) const {
  Duration need = travel->travel(from, to, depart);
  if (window_travel) need = std::max(need, window_travel->travel(from, to, depart));
  return depart + need;
}

Status validate(const Problem& p) {
  if (!p.travel) return Error::invalid("problem: no travel oracle");
  const std::size_t locations = p.travel->location_count();
  if (p.window_travel && p.window_travel->location_count() != locations)
    return Error::invalid(fmt::format("problem: the window travel has {} locations, the travel {}",
                                      p.window_travel->location_count(), locations));
  if (p.robot.location >= locations)
    return Error::invalid(fmt::format("robot: location {} out of range (0..{})", p.robot.location, locations));
  if (p.robot.capacity < 0) return Error::invalid("robot: capacity must not be negative");
  if (p.return_to && p.return_to->location >= locations)
    return Error::invalid("return: location out of range");
  std::map<std::string, int> pickups, drops;
  std::map<std::string, int> on_board;
  for (const auto& item : p.robot.on_board) {
    if (++on_board[item.job] > 1) return Error::invalid(fmt::format("robot: job '{}' on board twice", item.job));
    if (item.load < 0) return Error::invalid(fmt::format("robot: item of job '{}' has a negative load", item.job));
  }
  for (std::size_t i = 0; i < p.tasks.size(); ++i) {
    const auto& t = p.tasks[i];
    auto bad = [&](std::string what) { return Error::invalid(fmt::format("task '{}': {}", t.id, what)); };
    if (t.start_location >= locations || t.end_location >= locations) return bad("location out of range");
    if (t.duration < Duration{0}) return bad("negative duration");
    if (t.latest_start() < t.release)
      return bad(fmt::format("window too short: latest start is {} before the release",
                             format_duration(t.release - t.latest_start())));
    for (std::size_t a : t.after) {
      if (a >= p.tasks.size()) return bad("`after` index out of range");
      if (a == i) return bad("is `after` itself");
    }
    if (t.transfer) {
      if (t.transfer->load < 0) return bad("negative load");
      (t.transfer->action == ItemAction::kPickup ? pickups : drops)[t.transfer->job]++;
    }
  }
  for (const auto& [job, count] : pickups) {
    if (count > 1) return Error::invalid(fmt::format("job '{}': more than one pickup", job));
    if (on_board.count(job)) return Error::invalid(fmt::format("job '{}': picked up but already on board", job));
  }
  for (const auto& [job, count] : drops) {
    if (count > 1) return Error::invalid(fmt::format("job '{}': more than one drop", job));
    if (!pickups.count(job) && !on_board.count(job))
      return Error::invalid(fmt::format("job '{}': dropped but never picked up nor on board", job));
  }
  for (const auto& [job, count] : pickups)
    if (!drops.count(job)) return Error::invalid(fmt::format("job '{}': picked up but never dropped", job));
  return check_acyclic(p);
}

}  // namespace rondo::schedule
