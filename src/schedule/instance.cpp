#include "instance.h"

#include <algorithm>
#include <map>
#include <numeric>

namespace rondo::schedule::detail {

namespace {
std::int64_t ms(Duration d) { return d.count(); }
// Floyd-Warshall costs n^3; above this the direct lower bounds are used (still valid when the
// travel satisfies the triangle inequality, and only a heuristic's filter otherwise).
constexpr std::size_t kShortestPathMaxTasks = 320;
}  // namespace

Instance::Instance(const Problem& p) : problem_(&p), n_(p.tasks.size()) {
  const Time origin = p.robot.time;
  window_ = p.window_travel != nullptr;
  static_ = !p.travel->time_dependent() && !(window_ && p.window_travel->time_dependent());
  has_return_ = p.return_to.has_value();
  if (has_return_) return_latest_ = ms(p.return_to->deadline - origin);
  release_.resize(n_);
  latest_.resize(n_);
  duration_.resize(n_);
  for (std::size_t i = 0; i < n_; ++i) {
    const auto& t = p.tasks[i];
    release_[i] = std::max<std::int64_t>(0, ms(t.release - origin));
    latest_[i] = ms(t.latest_start() - origin);
    duration_[i] = ms(t.duration);
  }
  const std::size_t m = n_ + 1;
  gap_.assign(m * m, 0);
  if (static_) arc_.assign(m * m, 0);
  if (static_ && window_) window_arc_.assign(m * m, 0);
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = 0; b < m; ++b) {
      const bool to_return = b == n_;
      if (to_return && !has_return_) continue;
      const LocationIndex la = from_location(a), lb = to_location(b);
      if (static_) arc_[a * m + b] = ms(p.travel->travel(la, lb, origin));
      if (static_ && window_ && !to_return) window_arc_[a * m + b] = ms(p.window_travel->travel(la, lb, origin));
      gap_[a * m + b] = ms(p.travel->lower_bound(la, lb));
    }
  // Shortest paths through tasks: from the end of a, via tasks (their durations count), to b.
  if (n_ <= kShortestPathMaxTasks) {
    for (std::size_t k = 0; k < n_; ++k)
      for (std::size_t a = 0; a < m; ++a) {
        const std::int64_t via = gap_[a * m + k] + duration_[k];
        for (std::size_t b = 0; b < m; ++b)
          gap_[a * m + b] = std::min(gap_[a * m + b], via + gap_[k * m + b]);
      }
  }
  max_gap_.assign(m, 0);
  for (std::size_t a = 0; a < m; ++a)
    for (std::size_t b = 0; b < n_; ++b) max_gap_[a] = std::max(max_gap_[a], gap_[a * m + b]);
  by_latest_.resize(n_);
  std::iota(by_latest_.begin(), by_latest_.end(), std::size_t{0});
  by_earliest_end_ = by_latest_;
  std::sort(by_latest_.begin(), by_latest_.end(), [&](auto x, auto y) { return latest_[x] < latest_[y]; });
  std::sort(by_earliest_end_.begin(), by_earliest_end_.end(),
            [&](auto x, auto y) { return release_[x] + duration_[x] < release_[y] + duration_[y]; });
  min_step_ = kNever;
  for (std::size_t b = 0; b < n_; ++b) {
    std::int64_t in = kNever;
    for (std::size_t a = 0; a < m; ++a)
      if (a != b) in = std::min(in, gap_[a * m + b]);
    min_step_ = std::min(min_step_, in + duration_[b]);
  }
  if (n_ == 0) min_step_ = 0;

  // Rules.
  preds_.assign(n_, {});
  load_delta_.assign(n_, 0);
  look_alikes_.assign(n_, {});
  capacity_ = p.robot.capacity;
  std::map<std::string, std::size_t> pickup_of, drop_of;
  for (std::size_t i = 0; i < n_; ++i) {
    const auto& t = p.tasks[i];
    preds_[i] = t.after;
    if (t.transfer) {
      (t.transfer->action == ItemAction::kPickup ? pickup_of : drop_of)[t.transfer->job] = i;
      load_delta_[i] = t.transfer->action == ItemAction::kPickup ? t.transfer->load : -t.transfer->load;
    }
  }
  for (const auto& [job, d] : drop_of)
    if (auto it = pickup_of.find(job); it != pickup_of.end()) preds_[d].push_back(it->second);
  for (const auto& item : p.robot.on_board) initial_load_ += item.load;
  // Holders of each appearance: items on board and pickups.
  std::map<std::string, std::vector<std::pair<Holder, std::string>>> holders;
  for (const auto& item : p.robot.on_board) {
    if (item.appearance.empty()) continue;
    auto d = drop_of.find(item.job);
    holders[item.appearance].push_back({{kNone, d == drop_of.end() ? kNone : d->second}, item.job});
  }
  for (const auto& [job, pk] : pickup_of) {
    const auto& look = p.tasks[pk].transfer->appearance;
    if (look.empty()) continue;
    auto d = drop_of.find(job);
    holders[look].push_back({{pk, d == drop_of.end() ? kNone : d->second}, job});
  }
  for (const auto& [job, pk] : pickup_of) {
    const auto& look = p.tasks[pk].transfer->appearance;
    if (look.empty()) continue;
    for (const auto& [h, other_job] : holders[look])
      if (other_job != job) look_alikes_[pk].push_back(h);
  }
  has_rules_ = p.has_item_constraints() || p.has_precedence();
}

LocationIndex Instance::from_location(std::size_t from) const {
  return from == n_ ? problem_->robot.location : problem_->tasks[from].end_location;
}

LocationIndex Instance::to_location(std::size_t to) const {
  if (to == n_) return has_return_ ? problem_->return_to->location : problem_->robot.location;
  return problem_->tasks[to].start_location;
}

std::int64_t Instance::travel_dynamic(std::size_t from, std::size_t to, std::int64_t depart) const {
  if (to == n_ && !has_return_) return 0;
  return ms(problem_->travel->travel(from_location(from), to_location(to),
                                     problem_->robot.time + Duration{depart}));
}

std::int64_t Instance::window_travel_dynamic(std::size_t from, std::size_t to, std::int64_t depart) const {
  return ms(problem_->window_travel->travel(from_location(from), to_location(to),
                                            problem_->robot.time + Duration{depart}));
}

bool Instance::order_respects_rules(const std::vector<std::size_t>& order) const {
  if (!has_rules_) return true;
  std::vector<char> done(n_, 0);
  std::int64_t load = initial_load_;
  for (std::size_t j : order) {
    if (!allows(j, load, [&](std::size_t i) { return done[i] != 0; })) return false;
    load += load_delta_[j];
    done[j] = 1;
  }
  return true;
}

Instance::Timing Instance::time(const std::vector<std::size_t>& order) const {
  Timing t;
  std::int64_t now = 0, objective = 0;
  std::size_t last = n_;
  for (std::size_t j : order) {
    const std::int64_t start = std::max(release_[j], now + travel(last, j, now));
    if (start > latest_[j] || !window_allows(last, j, now)) return t;
    now = start + duration_[j];
    objective += now;
    last = j;
  }
  if (has_return_ && now + travel(last, n_, now) > return_latest_) return t;
  t.feasible = true;
  t.objective = objective;
  return t;
}

Schedule Instance::to_schedule(const std::vector<std::size_t>& order, SolveStatus status) const {
  Result<Schedule> s = time_order(*problem_, order);
  if (!s) return Schedule{.status = SolveStatus::kTimeout};
  s->status = status;
  return std::move(s).value();
}

}  // namespace rondo::schedule::detail
