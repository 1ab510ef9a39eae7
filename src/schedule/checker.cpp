// Deliberately written without any helper shared with the solvers: a second, plain reading of
// the rules of MISSION.md §2 and §5.
#include "rondo/schedule/checker.h"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

namespace rondo::schedule {

std::string CheckReport::summary() const {
  std::string s;
  for (const auto& v : violations) s += v + "\n";
  return s.empty() ? "ok" : s;
}

CheckReport check_schedule(const Problem& p, const Schedule& s) {
  CheckReport r;
  auto bad = [&](std::string what) { r.violations.push_back(std::move(what)); };
  const std::size_t n = p.tasks.size();
  std::vector<int> seen(n, 0);
  std::vector<long> position(n, -1);
  for (std::size_t k = 0; k < s.entries.size(); ++k) {
    const std::size_t i = s.entries[k].task;
    if (i >= n) {
      bad(fmt::format("entry {}: task index {} out of range", k, i));
      return r;
    }
    ++seen[i];
    position[i] = static_cast<long>(k);
  }
  for (const auto& d : s.dropped) {
    if (d.task >= n) {
      bad(fmt::format("dropped task index {} out of range", d.task));
      return r;
    }
    ++seen[d.task];
    if (d.reason.empty()) bad(fmt::format("dropped task '{}' has no reason", p.tasks[d.task].id));
  }
  const bool complete = s.status == SolveStatus::kOptimal || s.status == SolveStatus::kFeasible;
  for (std::size_t i = 0; i < n; ++i) {
    if (seen[i] > 1) bad(fmt::format("task '{}' appears {} times", p.tasks[i].id, seen[i]));
    if (complete && seen[i] == 0) bad(fmt::format("task '{}' neither scheduled nor dropped", p.tasks[i].id));
  }

  Time previous_end = p.robot.time;
  LocationIndex here = p.robot.location;
  Duration objective{0};
  std::int64_t load = 0;
  std::map<std::string, int> looks;  // appearance -> items on board
  std::set<std::string> jobs_on_board;
  for (const auto& item : p.robot.on_board) {
    load += item.load;
    jobs_on_board.insert(item.job);
    if (!item.appearance.empty()) looks[item.appearance]++;
  }
  for (std::size_t k = 0; k < s.entries.size(); ++k) {
    const ScheduledTask& e = s.entries[k];
    const ProblemTask& t = p.tasks[e.task];
    const std::string& id = t.id;
    if (e.depart != previous_end)
      bad(fmt::format("'{}': departs at {} but the previous task ends at {}", id, format_time(e.depart),
                      format_time(previous_end)));
    const Duration need = p.travel->travel(here, t.start_location, e.depart);
    if (e.arrival < e.depart + need)
      bad(fmt::format("'{}': arrives {} after leaving, travel takes {}", id, format_duration(e.arrival - e.depart),
                      format_duration(need)));
    if (p.window_travel) {
      const Duration risk = std::max(need, p.window_travel->travel(here, t.start_location, e.depart));
      if (e.depart + risk > t.latest_start())
        bad(fmt::format("'{}': leaves at {} with {} of travel to allow for, after its latest start {}", id,
                        format_time(e.depart), format_duration(risk), format_time(t.latest_start())));
    }
    if (e.start < e.arrival) bad(fmt::format("'{}': starts before arriving", id));
    if (e.start < t.release) bad(fmt::format("'{}': starts before its release", id));
    if (e.end != e.start + t.duration) bad(fmt::format("'{}': end != start + duration", id));
    if (t.deadline_on == DeadlineOn::kEnd ? e.end > t.deadline : e.start > t.deadline)
      bad(fmt::format("'{}': misses its deadline {}", id, format_time(t.deadline)));
    if (e.start < previous_end) bad(fmt::format("'{}': overlaps the previous task", id));
    for (std::size_t a : t.after)
      if (a < n && (position[a] < 0 || position[a] >= static_cast<long>(k)))
        bad(fmt::format("'{}': runs before (or without) '{}', which must end first", id, p.tasks[a].id));
    if (t.transfer) {
      const ItemTransfer& x = t.transfer.value();
      if (x.action == ItemAction::kPickup) {
        load += x.load;
        if (p.robot.capacity > 0 && load > p.robot.capacity)
          bad(fmt::format("'{}': load {} exceeds capacity {}", id, load, p.robot.capacity));
        if (!x.appearance.empty() && looks[x.appearance]++ > 0)
          bad(fmt::format("'{}': picks up a second item that looks like '{}'", id, x.appearance));
        jobs_on_board.insert(x.job);
      } else {
        if (!jobs_on_board.count(x.job)) bad(fmt::format("'{}': drops job '{}' that is not on board", id, x.job));
        jobs_on_board.erase(x.job);
        load -= x.load;
        if (!x.appearance.empty()) looks[x.appearance]--;
      }
    }
    objective += e.end - p.robot.time;
    previous_end = e.end;
    here = t.end_location;
  }
  if (p.return_to && complete) {
    const Time back = previous_end + p.travel->travel(here, p.return_to->location, previous_end);
    if (back > p.return_to->deadline)
      bad(fmt::format("returns at {} after the deadline {}", format_time(back), format_time(p.return_to->deadline)));
  }
  r.recomputed_objective = objective;
  if (objective != s.objective)
    bad(fmt::format("reported objective {} ms, recomputed {} ms", s.objective.count(), objective.count()));
  if (s.lower_bound && *s.lower_bound > s.objective && complete)
    bad("lower bound above the objective");
  return r;
}

}  // namespace rondo::schedule
