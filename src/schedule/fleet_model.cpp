#include "fleet_model.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

namespace rondo::schedule::detail {

namespace {

std::int64_t ms_since_epoch(Time t) { return t.time_since_epoch().count(); }

}  // namespace

FleetModel::FleetModel(const FleetProblem& problem)
    : p_(&problem),
      n_(static_cast<int>(problem.tasks.size())),
      m_(static_cast<int>(problem.robots.size())),
      locations_(problem.travel->location_count()) {
  origin_ = ms_since_epoch(problem.robots.front().free_from);
  for (const FleetRobot& r : problem.robots) origin_ = std::min(origin_, ms_since_epoch(r.free_from));
  compile_robots();
  compile_tasks();
  compile_requests();
  compile_groups();
  neighbours_.resize(requests_.size());
  neighbours_known_.assign(requests_.size(), 0);
  compile_kinds();
  simple_ = static_ && !has_looks_ && !has_after_;
  for (int i = 0; i < n_ && simple_; ++i) simple_ = load_[i] >= 0 && request_of_[i] >= 0 && requests_[request_of_[i]].drop < 0;
}

void FleetModel::compile_robots() {
  std::map<std::pair<const TravelOracle*, double>, int> known;
  for (int r = 0; r < m_; ++r) {
    const FleetRobot& robot = p_->robots[r];
    const TravelOracle* oracle = &p_->travel_of(r);
    auto [it, fresh] = known.try_emplace({oracle, robot.speed_factor}, static_cast<int>(profiles_.size()));
    if (fresh) {
      Profile profile{.oracle = oracle, .speed = robot.speed_factor};
      if (robot.speed_factor == 1.0) profile.direct = dynamic_cast<const MatrixTravel*>(oracle);
      if (profile.direct == nullptr && !oracle->time_dependent()) {
        profile.matrix.resize(locations_ * locations_);
        for (std::size_t a = 0; a < locations_; ++a)
          for (std::size_t b = 0; b < locations_; ++b)
            profile.matrix[a * locations_ + b] = robot_travel(*p_, r, a, b, robot.free_from).count();
      } else if (profile.direct == nullptr) {
        static_ = false;
      }
      profiles_.push_back(std::move(profile));
    }
    profile_of_.push_back(it->second);
    free_from_.push_back(ms_since_epoch(robot.free_from) - origin_);
    robot_start_.push_back(robot.location);
    end_loc_robot_.push_back(robot.end ? static_cast<long>(robot.end->location) : -1L);
    end_latest_.push_back(robot.end ? ms_since_epoch(robot.end->deadline) - origin_ : kFleetNever);
    capacity_.push_back(robot.capacity > 0 ? robot.capacity : kFleetNever);
  }
}

void FleetModel::compile_tasks() {
  std::map<std::string, int> looks;
  allowed_.assign(static_cast<std::size_t>(m_) * n_, 1);
  preds_.resize(n_);
  succs_.resize(n_);
  for (int i = 0; i < n_; ++i) {
    const FleetTask& f = p_->tasks[i];
    const ProblemTask& t = f.task;
    release_.push_back(ms_since_epoch(t.release) - origin_);
    latest_.push_back(ms_since_epoch(t.latest_start()) - origin_);
    duration_.push_back(t.duration.count());
    start_loc_.push_back(t.start_location);
    end_loc_.push_back(t.end_location);
    std::int64_t load = f.demand;
    int look = -1;
    if (t.transfer) {
      load += t.transfer->action == ItemAction::kPickup ? t.transfer->load : -t.transfer->load;
      if (!t.transfer->appearance.empty()) {
        look = looks.try_emplace(t.transfer->appearance, static_cast<int>(looks.size())).first->second;
        has_looks_ = true;
      }
    }
    load_.push_back(load);
    look_.push_back(look);
    drop_cost_.push_back(p_->costs.drop_seconds * (1 + t.priority));
    has_due_ = has_due_ || f.due.has_value();
    for (std::size_t a : t.after) {
      preds_[i].push_back(static_cast<int>(a));
      succs_[a].push_back(i);
      has_after_ = true;
    }
    for (int r = 0; r < m_; ++r) {
      const FleetRobot& robot = p_->robots[r];
      bool ok = !f.pinned_robot || *f.pinned_robot == static_cast<std::size_t>(r);
      if (!f.action.empty()) ok = ok && std::find(robot.actions.begin(), robot.actions.end(), f.action) != robot.actions.end();
      allowed_[static_cast<std::size_t>(r) * n_ + i] = ok ? 1 : 0;
    }
  }
}

// A pickup with its drop is one request; every other task is a request of its own. Demands of
// the routing benchmarks (customers with a load and no drop) are plain tasks with a load.
void FleetModel::compile_requests() {
  request_of_.assign(n_, -1);
  std::map<std::string, int> drop_of;
  for (int i = 0; i < n_; ++i) {
    const auto& x = p_->tasks[i].task.transfer;
    if (x && x->action == ItemAction::kDrop) drop_of[x->job] = i;
  }
  for (int i = 0; i < n_; ++i) {
    const auto& x = p_->tasks[i].task.transfer;
    if (x && x->action == ItemAction::kDrop) continue;
    Request r{.first = i};
    if (x && x->action == ItemAction::kPickup) r.drop = drop_of.at(x->job);
    request_of_[i] = static_cast<int>(requests_.size());
    if (r.drop >= 0) request_of_[r.drop] = static_cast<int>(requests_.size());
    requests_.push_back(r);
  }
}

// Union-find over `after` links and deliveries: a group runs on one robot.
void FleetModel::compile_groups() {
  std::vector<int> parent(n_);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (int i = 0; i < n_; ++i)
    for (int a : preds_[i]) parent[find(a)] = find(i);
  for (const Request& r : requests_)
    if (r.drop >= 0) parent[find(r.drop)] = find(r.first);
  group_.resize(n_);
  for (int i = 0; i < n_; ++i) group_[i] = find(i);
}

const std::vector<int>& FleetModel::neighbours(int a) const {
  if (neighbours_known_[a]) return neighbours_[a];
  const int q = static_cast<int>(requests_.size());
  const int keep = std::min(40, q - 1);
  std::vector<std::pair<double, int>> by;
  const std::size_t la = start_loc_[requests_[a].first];
  for (int b = 0; b < q; ++b)
    if (b != a) by.emplace_back(distance(la, start_loc_[requests_[b].first]), b);
  if (keep > 0) std::partial_sort(by.begin(), by.begin() + keep, by.end());
  for (int k = 0; k < keep; ++k) neighbours_[a].push_back(by[k].second);
  neighbours_known_[a] = 1;
  return neighbours_[a];
}

double FleetModel::lower_bound_seconds(std::size_t from, std::size_t to) const {
  return to_seconds(p_->travel->lower_bound(from, to));
}

void FleetModel::compile_kinds() {
  kind_.resize(m_);
  for (int r = 0; r < m_; ++r) {
    kind_[r] = r;
    for (int k = 0; k < r; ++k) {
      if (kind_[k] != k) continue;
      const bool alike = same_ends(r, k) && free_from_[r] == free_from_[k] && robot_start_[r] == robot_start_[k] &&
                         capacity_[r] == capacity_[k] &&
                         std::equal(allowed_.begin() + static_cast<long>(r) * n_, allowed_.begin() + static_cast<long>(r + 1) * n_,
                                    allowed_.begin() + static_cast<long>(k) * n_);
      if (alike) {
        kind_[r] = k;
        break;
      }
    }
  }
}

double FleetModel::lateness_cost(int i, std::int64_t end) const {
  const auto& due = p_->tasks[i].due;
  if (!due) return 0;
  const std::int64_t late = end + origin_ - ms_since_epoch(*due);
  return late > 0 ? p_->costs.lateness_per_second * (static_cast<double>(late) / 1000.0) * (1 + priority(i)) : 0;
}

bool FleetModel::same_ends(int a, int b) const {
  return profile_of_[a] == profile_of_[b] && end_loc_robot_[a] == end_loc_robot_[b] && end_latest_[a] == end_latest_[b];
}

std::int64_t FleetModel::travel_dynamic(const Profile& profile, std::size_t from, std::size_t to,
                                        std::int64_t depart) const {
  const Duration d = profile.oracle->travel(from, to, Time{Duration{depart + origin_}});
  if (profile.speed == 1.0) return d.count();
  return static_cast<std::int64_t>(std::ceil(static_cast<double>(d.count()) / profile.speed));
}

}  // namespace rondo::schedule::detail
