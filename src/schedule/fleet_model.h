// The fleet solver's compiled view of a FleetProblem: times as int64 milliseconds from the
// earliest robot's free_from, tasks grouped into requests (a pickup with its drop, or one task),
// per-robot travel through profiles (a cached matrix when the oracle is static), the same-robot
// groups of `after` links and deliveries, and each task's nearest others. Private to src/schedule.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "rondo/schedule/fleet_problem.h"

namespace rondo::schedule::detail {

inline constexpr std::int64_t kFleetNever = INT64_MAX / 4;

// One unit of insertion and removal: a single task (drop < 0) or a pickup and its drop.
struct Request {
  int first = -1;  // the task, or the pickup
  int drop = -1;   // the drop of a delivery, or -1
};

class FleetModel {
 public:
  explicit FleetModel(const FleetProblem& problem);

  const FleetProblem& problem() const { return *p_; }
  int tasks() const { return n_; }
  int robots() const { return m_; }
  bool hierarchical() const { return p_->objective == FleetObjective::kVehiclesThenDistance; }
  // Static travel on every robot, no item rules and no `after` links: the O(1) insertion test on
  // latest starts and the route's total load is exact.
  bool simple() const { return simple_; }
  bool static_travel() const { return static_; }
  bool has_looks() const { return has_looks_; }
  bool has_after() const { return has_after_; }
  bool has_due() const { return has_due_; }  // some task has a soft due time

  std::int64_t release(int i) const { return release_[i]; }
  std::int64_t latest(int i) const { return latest_[i]; }
  std::int64_t duration(int i) const { return duration_[i]; }
  std::size_t start_location(int i) const { return start_loc_[i]; }
  std::size_t end_location(int i) const { return end_loc_[i]; }
  std::int64_t load(int i) const { return load_[i]; }
  int look(int i) const { return look_[i]; }  // -1: looks like nothing else
  int priority(int i) const { return p_->tasks[i].task.priority; }
  double drop_cost(int i) const { return drop_cost_[i]; }
  double lateness_cost(int i, std::int64_t end) const;  // 0 without a due time
  const std::vector<int>& predecessors(int i) const { return preds_[i]; }
  const std::vector<int>& successors(int i) const { return succs_[i]; }
  int group(int i) const { return group_[i]; }  // same group => same robot
  bool allowed(int robot, int task) const { return allowed_[static_cast<std::size_t>(robot) * n_ + task] != 0; }

  const std::vector<Request>& requests() const { return requests_; }
  int request_of(int task) const { return request_of_[task]; }
  // Requests by increasing distance from request r (first tasks' start locations), at most 40;
  // computed when first asked for (an insertion into a large plan asks for few).
  const std::vector<int>& neighbours(int r) const;

  std::int64_t free_from(int robot) const { return free_from_[robot]; }
  std::size_t robot_start(int robot) const { return robot_start_[robot]; }
  bool has_end(int robot) const { return end_loc_robot_[robot] >= 0; }
  std::size_t robot_end(int robot) const { return static_cast<std::size_t>(end_loc_robot_[robot]); }
  std::int64_t end_latest(int robot) const { return end_latest_[robot]; }
  std::int64_t capacity(int robot) const { return capacity_[robot]; }
  // The first robot identical to this one (start, time, dock, capacity, travel, what it may run):
  // empty robots of one kind are interchangeable.
  int kind(int robot) const { return kind_[robot]; }
  // Robots alike for tail exchanges: same travel profile, dock and dock deadline.
  bool same_ends(int a, int b) const;

  std::int64_t travel(int robot, std::size_t from, std::size_t to, std::int64_t depart) const {
    const Profile& profile = profiles_[profile_of_[robot]];
    if (profile.direct != nullptr) return profile.direct->at(from, to).count();
    if (!profile.matrix.empty()) return profile.matrix[from * locations_ + to];
    return travel_dynamic(profile, from, to, depart);
  }
  double distance(std::size_t from, std::size_t to) const {
    return p_->distance.empty() ? lower_bound_seconds(from, to) : p_->distance[from * locations_ + to];
  }
  std::int64_t origin_ms() const { return origin_; }  // free_from of the earliest robot, as ms since the epoch

 private:
  double lower_bound_seconds(std::size_t from, std::size_t to) const;
  struct Profile;
  std::int64_t travel_dynamic(const Profile& profile, std::size_t from, std::size_t to, std::int64_t depart) const;
  struct Profile {
    const TravelOracle* oracle = nullptr;
    const MatrixTravel* direct = nullptr;  // a static matrix read in place (speed factor 1)
    double speed = 1;
    std::vector<std::int64_t> matrix{};  // empty when time-dependent
  };
  void compile_tasks();
  void compile_robots();
  void compile_requests();
  void compile_groups();
  void compile_kinds();

  const FleetProblem* p_;
  int n_ = 0, m_ = 0;
  std::size_t locations_ = 0;
  std::int64_t origin_ = 0;
  bool simple_ = true, static_ = true, has_looks_ = false, has_after_ = false, has_due_ = false;
  std::vector<std::int64_t> release_, latest_, duration_, load_;
  std::vector<std::size_t> start_loc_, end_loc_;
  std::vector<int> look_, group_, request_of_;
  std::vector<double> drop_cost_;
  std::vector<std::vector<int>> preds_, succs_;
  mutable std::vector<std::vector<int>> neighbours_;
  mutable std::vector<char> neighbours_known_;
  std::vector<unsigned char> allowed_;
  std::vector<Request> requests_;
  std::vector<std::int64_t> free_from_, end_latest_, capacity_;
  std::vector<std::size_t> robot_start_;
  std::vector<long> end_loc_robot_;
  std::vector<int> profile_of_, kind_;
  std::vector<Profile> profiles_;
};

}  // namespace rondo::schedule::detail
