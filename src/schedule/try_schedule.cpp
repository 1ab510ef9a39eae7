#include "rondo/schedule/try_schedule.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

#include "instance.h"

namespace rondo::schedule {

namespace {

bool complete(const Schedule& s) { return s.status == SolveStatus::kOptimal || s.status == SolveStatus::kFeasible; }

// The problem restricted to the kept tasks; `index` maps its tasks back to the original ones.
Problem subproblem(const Problem& p, const std::vector<bool>& keep, std::vector<std::size_t>& index) {
  Problem q = p;
  q.tasks.clear();
  index.clear();
  std::vector<std::size_t> remap(p.tasks.size(), SIZE_MAX);
  for (std::size_t i = 0; i < p.tasks.size(); ++i)
    if (keep[i]) {
      remap[i] = q.tasks.size();
      index.push_back(i);
      q.tasks.push_back(p.tasks[i]);
    }
  for (auto& t : q.tasks) {
    std::vector<std::size_t> after;
    for (std::size_t a : t.after)
      if (remap[a] != SIZE_MAX) after.push_back(remap[a]);
    t.after = std::move(after);
  }
  return q;
}

// A pickup and its drop stand or fall together; so do tasks chained by `after`.
void close_drops(const Problem& p, std::vector<bool>& keep) {
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = 0; i < p.tasks.size(); ++i) {
      if (!keep[i]) continue;
      for (std::size_t a : p.tasks[i].after)
        if (!keep[a]) keep[i] = false, changed = true;
      const auto& x = p.tasks[i].transfer;
      if (!keep[i] || !x) continue;
      for (std::size_t j = 0; j < p.tasks.size(); ++j)
        if (j != i && !keep[j] && p.tasks[j].transfer && p.tasks[j].transfer->job == x->job)
          keep[i] = false, changed = true;
    }
  }
}

// Cheap and bounded, for when the budget ends before the solver has answered (a takeover that
// brings many new tasks at once): `order` (indices into p.tasks, feasible) with each candidate
// inserted in turn, the highest priority first, where it delays the tasks least, if anywhere that
// keeps every task in its window and the item and precedence rules. No solver call: for k
// candidates, k n timing checks of O(n) at most (fewer: no place after c's latest start is tried). Marks what it placed
// in `keep`. Nothing when `order` itself is infeasible.
std::optional<std::vector<std::size_t>> insert_where_they_fit(const Problem& p, std::vector<std::size_t> order,
                                                              std::vector<std::size_t> candidates,
                                                              std::vector<bool>& keep) {
  const detail::Instance in(p);
  if (!in.time(order).feasible || !in.order_respects_rules(order)) return std::nullopt;
  std::stable_sort(candidates.begin(), candidates.end(), [&](std::size_t a, std::size_t b) {
    if (p.tasks[a].priority != p.tasks[b].priority) return p.tasks[a].priority > p.tasks[b].priority;
    return in.latest(a) < in.latest(b);
  });
  std::vector<std::size_t> placed;
  for (std::size_t c : candidates) {
    // When each prefix of the plan ends: c starts after it, so once one ends past c's latest start,
    // no later place is tried (prefixes only end later).
    std::vector<std::int64_t> prefix_end{0};
    std::size_t last = in.size();  // the robot's start
    for (std::size_t j : order) {
      const std::int64_t now = prefix_end.back();
      prefix_end.push_back(std::max(in.release(j), now + in.travel(last, j, now)) + in.duration(j));
      last = j;
    }
    std::optional<std::size_t> best_at;
    std::int64_t best_objective = 0;
    std::vector<std::size_t> trial{c};  // c at each place in turn: 0, then swapped one on
    trial.reserve(order.size() + 1);
    for (std::size_t i : order) trial.push_back(i);
    for (std::size_t at = 0;; ++at) {
      if (prefix_end[at] > in.latest(c)) break;
      const detail::Instance::Timing t = in.time(trial);
      if (t.feasible && (!best_at || t.objective < best_objective) && in.order_respects_rules(trial)) {
        best_at = at;
        best_objective = t.objective;
      }
      if (at == order.size()) break;
      std::swap(trial[at], trial[at + 1]);
    }
    if (!best_at) continue;
    std::vector<std::size_t> longer;
    longer.reserve(order.size() + 1);
    for (std::size_t k = 0; k <= order.size(); ++k) {
      if (k == *best_at) longer.push_back(c);
      if (k < order.size()) longer.push_back(order[k]);
    }
    order = std::move(longer);
    placed.push_back(c);
  }
  // A pickup placed without its drop (or a task without what it comes after) goes again.
  std::vector<bool> closed(p.tasks.size(), false);
  for (std::size_t i : order) closed[i] = true;
  close_drops(p, closed);
  std::vector<std::size_t> kept_order;
  for (std::size_t i : order)
    if (closed[i]) kept_order.push_back(i);
  if (kept_order.size() != order.size() && (!in.time(kept_order).feasible || !in.order_respects_rules(kept_order)))
    return std::nullopt;
  for (std::size_t i : placed)
    if (closed[i]) keep[i] = true;
  return kept_order;
}

// The schedule of `order` (indices into p.tasks) as the solver would give it for the subproblem of
// the kept tasks, with `index` mapping back.
Schedule schedule_of(const Problem& p, const std::vector<std::size_t>& order, const std::vector<bool>& keep,
                     std::vector<std::size_t>& index) {
  const Problem q = subproblem(p, keep, index);
  std::vector<std::size_t> to_q(p.tasks.size(), SIZE_MAX);
  for (std::size_t k = 0; k < index.size(); ++k) to_q[index[k]] = k;
  std::vector<std::size_t> q_order;
  for (std::size_t i : order) q_order.push_back(to_q[i]);
  return detail::Instance(q).to_schedule(q_order, SolveStatus::kFeasible);
}

// Local clock times, the zone named once: "10:00–10:15 GMT".
std::string hhmm(const TimeZone& zone, Time t) { return zone.format_clock(t).substr(0, 5); }

DroppedTask reason_for(const Problem& p, std::size_t i, const Schedule& kept, const std::vector<std::size_t>& index,
                       const TimeZone& zone) {
  const ProblemTask& t = p.tasks[i];
  const std::string window = fmt::format("window {}–{}", hhmm(zone, t.release), zone.format_clock(t.deadline));
  // Alone from the robot's position?
  // Travel as the window check counts it (with a chance constraint, its quantile).
  const Duration first_travel = p.window_arrival(p.robot.location, t.start_location, p.robot.time) - p.robot.time;
  if (p.robot.time + first_travel > t.latest_start())
    return {i,
            fmt::format("{} cannot be reached from the robot's position at {} (travel {})", window,
                        zone.format_clock(p.robot.time), format_duration(first_travel)),
            DropCause::kUnreachable};
  // Where would it go? After the last kept task that starts before its latest start.
  std::vector<std::string> stronger;
  for (const auto& e : kept.entries) {
    const ProblemTask& k = p.tasks[index[e.task]];
    if (k.priority > t.priority && e.end > t.release && e.start < t.deadline) stronger.push_back(k.id);
  }
  std::string where;
  const ScheduledTask* before = nullptr;
  for (const auto& e : kept.entries)
    if (e.end <= t.latest_start()) before = &e;
  if (before != nullptr) {
    const ProblemTask& b = p.tasks[index[before->task]];
    const Duration leg = p.window_arrival(b.end_location, t.start_location, before->end) - before->end;
    if (before->end + leg > t.latest_start())
      where = fmt::format("{} cannot be reached after task {} ends at {} (travel {})", window, b.id,
                          zone.format_clock(before->end), format_duration(leg));
  }
  if (where.empty()) where = fmt::format("{} does not fit between the kept tasks", window);
  if (!stronger.empty()) {
    std::string list;
    for (const auto& s : stronger) list += (list.empty() ? "" : ", ") + s;
    return {i, fmt::format("{}; dropped for higher-priority tasks {}", where, list), DropCause::kHigherPriority};
  }
  return {i, fmt::format("{}; lowest priority ({}) among the new tasks that did not fit", where, t.priority),
          DropCause::kLowestPriority};
}

}  // namespace

// Bounded by `stop` (docs/scheduling.md, "Within the budget"): once it fires before the solver has
// found a schedule, no further solver call is made and no task is dropped for want of time.
TryScheduleResult try_schedule(const TryScheduleRequest& request, Scheduler& solver, const StopCondition& stop,
                               std::mt19937_64& rng) {
  const Problem& p = request.problem;
  TryScheduleResult out;
  std::vector<bool> keep(p.tasks.size(), true);
  std::vector<std::size_t> remaining = request.new_tasks;  // new tasks not dropped yet
  std::vector<std::size_t> dropped_order;
  std::vector<std::size_t> index;
  Schedule found;
  std::string blocked_by;  // set when a non-interruptible running task forced drops

  auto attempt = [&]() {
    ++out.attempts;
    const Problem q = subproblem(p, keep, index);
    found = solver.solve(q, stop);
    return complete(found);
  };

  // The budget ended before the solver answered: a failed attempt then says nothing about what
  // fits, and every further one would fail at once and drop every new task. Instead keep the old
  // tasks in the order they came in (the plan they are from; by latest start if that no longer
  // holds) and insert the new ones where they fit; the rest are dropped (for now, to the executor).
  const auto settle_by_insertion = [&]() {
    std::vector<std::size_t> old_order;
    for (std::size_t i = 0; i < p.tasks.size(); ++i)
      if (std::find(request.new_tasks.begin(), request.new_tasks.end(), i) == request.new_tasks.end())
        old_order.push_back(i);
    std::fill(keep.begin(), keep.end(), false);
    for (std::size_t i : old_order) keep[i] = true;
    std::optional<std::vector<std::size_t>> order = insert_where_they_fit(p, old_order, request.new_tasks, keep);
    if (!order) {
      std::stable_sort(old_order.begin(), old_order.end(), [&](std::size_t a, std::size_t b) {
        return p.tasks[a].latest_start() < p.tasks[b].latest_start();
      });
      order = insert_where_they_fit(p, old_order, request.new_tasks, keep);
    }
    if (order) found = schedule_of(p, *order, keep, index);
    return order.has_value() && complete(found);
  };
  bool by_insertion = false;
  while (!attempt()) {
    if (found.status == SolveStatus::kTimeout && stop.should_stop()) {
      by_insertion = settle_by_insertion();
      if (by_insertion) break;
      remaining.clear();  // the old tasks fit neither order: as when they are infeasible
    }
    if (remaining.empty()) {
      out.outcome = TryScheduleOutcome::kOldTasksInfeasible;
      out.schedule.status = found.status;
      for (std::size_t i : request.new_tasks)
        out.schedule.dropped.push_back({i, "the tasks already accepted leave no room for it", DropCause::kDoesNotFit});
      return out;
    }
    // The lowest-priority 20 % (at least one), ties broken at random.
    std::shuffle(remaining.begin(), remaining.end(), rng);
    std::stable_sort(remaining.begin(), remaining.end(),
                     [&](std::size_t a, std::size_t b) { return p.tasks[a].priority < p.tasks[b].priority; });
    const std::size_t count = std::max<std::size_t>(1, (remaining.size() + 4) / 5);
    std::vector<std::size_t> victims(remaining.begin(), remaining.begin() + static_cast<std::ptrdiff_t>(count));
    if (request.running) {
      std::vector<std::string> higher;
      for (std::size_t v : victims)
        if (p.tasks[v].priority > request.running->priority &&
            std::find(request.cannot_preempt.begin(), request.cannot_preempt.end(), v) == request.cannot_preempt.end())
          higher.push_back(p.tasks[v].id);
      if (!higher.empty()) {
        std::string list;
        for (const auto& h : higher) list += (list.empty() ? "" : ", ") + h;
        if (request.running->interruptible) {
          out.outcome = TryScheduleOutcome::kPreemptRunning;
          out.preempt_reason = fmt::format("tasks {} outrank the running task {} (priority {} > {}) and do not fit "
                                           "while it runs: interrupt it and schedule again",
                                           list, request.running->id, p.tasks[victims.front()].priority,
                                           request.running->priority);
          return out;
        }
        blocked_by = request.running->id;
      }
    }
    remaining.erase(remaining.begin(), remaining.begin() + static_cast<std::ptrdiff_t>(count));
    for (std::size_t v : victims) {
      keep[v] = false;
      dropped_order.push_back(v);
    }
    close_drops(p, keep);
    std::erase_if(remaining, [&](std::size_t i) { return !keep[i]; });
  }
  Schedule best = found;
  std::vector<std::size_t> best_index = index;

  if (request.policy == DropPolicy::kPaperThenRestore && !dropped_order.empty() && !by_insertion) {
    std::vector<std::size_t> back = dropped_order;
    std::stable_sort(back.begin(), back.end(),
                     [&](std::size_t a, std::size_t b) { return p.tasks[a].priority > p.tasks[b].priority; });
    for (std::size_t v : back) {
      if (keep[v]) continue;
      if (stop.should_stop()) {  // no budget left to solve: what is left goes in where it fits
        std::vector<std::size_t> order, rest;
        for (const ScheduledTask& e : best.entries) order.push_back(best_index[e.task]);
        for (std::size_t r : back)
          if (!keep[r]) rest.push_back(r);
        if (auto more = insert_where_they_fit(p, order, rest, keep)) {
          Schedule s = schedule_of(p, *more, keep, index);
          if (complete(s)) {
            best = std::move(s);
            best_index = index;
          } else {
            for (std::size_t r : rest) keep[r] = false;
          }
        }
        break;
      }
      keep[v] = true;
      // Its delivery partner comes back with it.
      std::vector<std::size_t> partners;
      for (std::size_t j = 0; j < p.tasks.size(); ++j)
        if (!keep[j] && p.tasks[v].transfer && p.tasks[j].transfer && p.tasks[j].transfer->job == p.tasks[v].transfer->job) {
          keep[j] = true;
          partners.push_back(j);
        }
      std::vector<bool> closed = keep;
      close_drops(p, closed);
      if (closed == keep && attempt()) {
        best = found;
        best_index = index;
      } else {
        keep[v] = false;
        for (std::size_t j : partners) keep[j] = false;
      }
    }
  }

  // Map back to the original task indices and explain each drop.
  Schedule s = best;
  for (auto& e : s.entries) e.task = best_index[e.task];
  s.dropped.clear();
  for (std::size_t i = 0; i < p.tasks.size(); ++i) {
    if (keep[i]) continue;
    DroppedTask d = reason_for(p, i, best, best_index, request.zone);
    if (!blocked_by.empty() && request.running && p.tasks[i].priority > request.running->priority)
      d.reason += fmt::format("; the running task {} cannot be interrupted", blocked_by);
    s.dropped.push_back(std::move(d));
  }
  // The objective covers the scheduled tasks only (as the checker recomputes it).
  out.outcome = s.dropped.empty() ? TryScheduleOutcome::kAllScheduled : TryScheduleOutcome::kSomeDropped;
  out.schedule = std::move(s);
  return out;
}

}  // namespace rondo::schedule
