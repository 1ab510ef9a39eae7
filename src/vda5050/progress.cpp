#include "rondo/vda5050/progress.h"

#include <algorithm>
#include <cmath>

namespace rondo::vda5050 {

void ProgressTracker::order_sent(const Order& order, Time t) {
  if (order.nodes.empty()) return;
  const std::int64_t first = order.nodes.front().sequence_id;
  if (order.order_id != order_id_) {
    end_order();
    order_id_ = order.order_id;
    last_sequence_ = first;
    arrived_at_ = t;
  } else {
    // An update replaces everything from its stitch node on.
    nodes_.erase(nodes_.lower_bound(first), nodes_.end());
    edges_.erase(edges_.lower_bound(first), edges_.end());
    route_finished_ = false;
  }
  latest_update_id_ = order.order_update_id;
  for (const OrderNode& n : order.nodes) nodes_[n.sequence_id] = n.node_id;
  for (const OrderEdge& e : order.edges) edges_[e.sequence_id] = EdgeInfo{e, t};
}

void ProgressTracker::cancel_sent(const std::string& action_id, Time) {
  cancel_id_ = action_id;
}

void ProgressTracker::end_order() {
  order_id_.clear();
  nodes_.clear();
  edges_.clear();
  last_sequence_ = 0;
  latest_update_id_ = 0;
  waiting_reported_at_ = -1;
  route_finished_ = false;
  fault_in_current_edge_ = false;
}

const ProgressTracker::EdgeInfo* ProgressTracker::next_released_edge() const {
  auto it = edges_.find(last_sequence_ + 1);
  if (it == edges_.end() || !it->second.edge.released) return nullptr;
  return &it->second;
}

Time ProgressTracker::free_since(const EdgeInfo& e) const {
  return std::max({arrived_at_, e.released_at, fault_cleared_at_});
}

std::vector<ProgressEvent> ProgressTracker::observe(const State& state, Time t) {
  std::vector<ProgressEvent> out;
  track_route(state, t, out);
  track_actions(state, t, out);
  track_faults(state, t, out);
  track_rejections(state, out);
  track_battery(state, out);
  return out;
}

void ProgressTracker::finish_edges_up_to(std::int64_t sequence_id, Time t, std::vector<ProgressEvent>& out) {
  std::vector<const EdgeInfo*> passed;
  for (auto it = edges_.upper_bound(last_sequence_); it != edges_.end() && it->first < sequence_id; ++it) {
    passed.push_back(&it->second);
  }
  if (!passed.empty()) {
    const Time start = free_since(*passed.front());
    for (const EdgeInfo* e : passed) {
      EdgeAttempt a{.edge_id = e->edge.edge_id,
                    .from_node = e->edge.start_node_id,
                    .to_node = e->edge.end_node_id,
                    .sequence_id = e->edge.sequence_id,
                    .start = start,
                    .duration = t - start,
                    .outcome = fault_in_current_edge_ ? EdgeOutcome::kRobotFault : EdgeOutcome::kSucceeded,
                    .timed = passed.size() == 1};
      out.emplace_back(EdgeFinished{std::move(a)});
    }
  }
  last_sequence_ = sequence_id;
  arrived_at_ = t;
  fault_in_current_edge_ = false;
}

void ProgressTracker::end_current_edge(EdgeOutcome outcome, Time t, std::vector<ProgressEvent>& out) {
  const EdgeInfo* e = next_released_edge();
  if (e == nullptr || free_since(*e) > t) return;
  const Time start = free_since(*e);
  out.emplace_back(EdgeFinished{EdgeAttempt{
      .edge_id = e->edge.edge_id,
      .from_node = e->edge.start_node_id,
      .to_node = e->edge.end_node_id,
      .sequence_id = e->edge.sequence_id,
      .start = start,
      .duration = t - start,
      .outcome = (outcome == EdgeOutcome::kFailed && fault_in_current_edge_) ? EdgeOutcome::kRobotFault : outcome,
      .timed = true}});
}

void ProgressTracker::track_route(const State& s, Time t, std::vector<ProgressEvent>& out) {
  if (order_id_.empty() || s.order_id != order_id_) return;
  if (s.last_node_sequence_id > last_sequence_ && nodes_.count(s.last_node_sequence_id) != 0 &&
      nodes_.at(s.last_node_sequence_id) == s.last_node_id) {
    finish_edges_up_to(s.last_node_sequence_id, t, out);
  }
  // Judge the vehicle's order only once it shows the latest update.
  if (s.order_update_id < latest_update_id_) return;
  const bool edges_ahead = edges_.upper_bound(last_sequence_) != edges_.end();
  const bool vehicle_has_nothing_left = s.node_states.empty() && s.edge_states.empty();
  if (!edges_ahead) {
    if (vehicle_has_nothing_left && !route_finished_ && s.last_node_sequence_id == last_sequence_) {
      route_finished_ = true;
      out.emplace_back(RouteFinished{nodes_.count(last_sequence_) ? nodes_.at(last_sequence_) : ""});
    }
    return;
  }
  if (vehicle_has_nothing_left) {
    if (!cancel_id_) {
      // The vehicle dropped the order with edges still ahead: the edge it was on failed.
      end_current_edge(EdgeOutcome::kFailed, t, out);
      end_order();
    }
    return;
  }
  const bool horizon_only =
      std::none_of(s.node_states.begin(), s.node_states.end(), [](const NodeState& n) { return n.released; });
  if (next_released_edge() == nullptr && horizon_only && !s.driving && waiting_reported_at_ != last_sequence_) {
    waiting_reported_at_ = last_sequence_;
    out.emplace_back(WaitingForUpdate{nodes_.at(last_sequence_), last_sequence_});
  }
}

void ProgressTracker::track_actions(const State& s, Time t, std::vector<ProgressEvent>& out) {
  for (const ActionState& a : s.action_states) {
    auto it = actions_.find(a.action_id);
    if (it != actions_.end() && it->second == a.action_status) continue;
    actions_[a.action_id] = a.action_status;
    out.emplace_back(ActionChanged{a.action_id, a.action_type, a.action_status, a.result_description});
    const bool ended = a.action_status == ActionStatus::kFinished || a.action_status == ActionStatus::kFailed;
    if (cancel_id_ && a.action_id == *cancel_id_ && ended) {
      const bool succeeded = a.action_status == ActionStatus::kFinished;
      if (succeeded) {
        // The edge the vehicle was on ends cancelled, and with it the order.
        end_current_edge(EdgeOutcome::kCancelled, t, out);
        end_order();
      }
      out.emplace_back(CancelFinished{a.action_id, succeeded, a.result_description});
      cancel_id_.reset();
    }
  }
}

void ProgressTracker::track_faults(const State& s, Time t, std::vector<ProgressEvent>& out) {
  std::string reason;
  for (const VehicleError& e : s.errors) {
    if (e.error_level != ErrorLevel::kFatal) continue;
    if (!reason.empty()) reason += "; ";
    reason += "FATAL " + e.error_type + (e.error_description.empty() ? "" : ": " + e.error_description);
  }
  if (s.operating_mode != OperatingMode::kAutomatic) {
    if (!reason.empty()) reason += "; ";
    reason += std::string("operatingMode ") + to_string(s.operating_mode);
  }
  if (!reason.empty() && !fault_) {
    fault_ = reason;
    if (next_released_edge() != nullptr) fault_in_current_edge_ = true;
    out.emplace_back(FaultRaised{reason});
  } else if (reason.empty() && fault_) {
    fault_.reset();
    fault_cleared_at_ = t;
    out.emplace_back(FaultCleared{});
  }
}

void ProgressTracker::track_rejections(const State& s, std::vector<ProgressEvent>& out) {
  // Counted, not just present: a vehicle that rejects the same order twice lists the same error
  // twice, and the second rejection is news too.
  std::map<std::pair<std::string, std::string>, int> now;
  for (const VehicleError& e : s.errors) {
    if (e.error_type != "validationError" && e.error_type != "orderError" && e.error_type != "orderUpdateError" &&
        e.error_type != "noRouteError") {
      continue;
    }
    const int n = ++now[{e.error_type, e.error_description}];
    auto seen = rejections_.find({e.error_type, e.error_description});
    if (seen == rejections_.end() || seen->second < n) out.emplace_back(Rejected{e.error_type, e.error_description});
  }
  rejections_ = std::move(now);
}

void ProgressTracker::track_battery(const State& s, std::vector<ProgressEvent>& out) {
  BatteryChanged b{s.battery_state.battery_charge, s.battery_state.charging};
  if (!battery_ || battery_->charging != b.charging || std::floor(battery_->charge) != std::floor(b.charge)) {
    battery_ = b;
    out.emplace_back(b);
  }
}

}  // namespace rondo::vda5050
