// Progress of one vehicle's order, read from its successive state messages: a pure state
// machine, fed what rondo sent and what the vehicle reported, with the time each happened on
// rondo's clock (never the vehicle's timestamps, whose clock may be off).
//
//   ProgressTracker progress;
//   progress.order_sent(order, now);                   // and every update, when it is sent
//   for (const ProgressEvent& e : progress.observe(state, now)) {
//     if (auto* f = std::get_if<EdgeFinished>(&e)) log_traversal(f->attempt);
//   }
//
// Edges: the vehicle is at the node with the highest sequenceId it reported (lastNodeSequenceId);
// when that moves past an edge, the edge attempt finished. Its start is when the vehicle was last
// free to drive it: the latest of its arrival at the start node, the edge's release and the end
// of the last fault. It ends with a cancel (the cancelOrder FINISHED or FAILED while on it), or
// failed when the vehicle drops the order with the edge still ahead; an attempt during which a
// fault began counts as a robot fault, not as learning data.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "rondo/core/time.h"
#include "rondo/exec/robot.h"
#include "rondo/vda5050/messages.h"

namespace rondo::vda5050 {

// How an edge attempt ended: the executor's own outcome (exec/robot.h), one name for one thing.
using exec::EdgeOutcome;

struct EdgeAttempt {
  std::string edge_id;
  std::string from_node;
  std::string to_node;
  std::int64_t sequence_id = 0;
  Time start{};
  Duration duration{0};
  EdgeOutcome outcome = EdgeOutcome::kSucceeded;
  // False when several edges finished between two state messages: then each of them only lies
  // somewhere in [start, start + duration], which is not a measured traversal time.
  bool timed = true;
  bool operator==(const EdgeAttempt&) const = default;
};

struct EdgeFinished {
  EdgeAttempt attempt;
  bool operator==(const EdgeFinished&) const = default;
};
struct ActionChanged {
  std::string action_id;
  std::string action_type;
  ActionStatus status = ActionStatus::kWaiting;
  std::string result_description;
  bool operator==(const ActionChanged&) const = default;
};
// The vehicle finished the base and stands at its last node; the horizon is still ahead. It is
// waiting for an order update: not stuck, and not done.
struct WaitingForUpdate {
  std::string node_id;
  std::int64_t sequence_id = 0;
  bool operator==(const WaitingForUpdate&) const = default;
};
// Every node and edge of the order is traversed (node actions are reported on their own).
struct RouteFinished {
  std::string node_id;
  bool operator==(const RouteFinished&) const = default;
};
// The vehicle reported the cancelOrder instant action FINISHED (succeeded) or FAILED.
struct CancelFinished {
  std::string action_id;
  bool succeeded = false;
  std::string result_description;
  bool operator==(const CancelFinished&) const = default;
};
struct FaultRaised {
  std::string reason;
  bool operator==(const FaultRaised&) const = default;
};
struct FaultCleared {
  bool operator==(const FaultCleared&) const = default;
};
struct BatteryChanged {
  double charge = 0;  // percent
  bool charging = false;
  bool operator==(const BatteryChanged&) const = default;
};
// A validationError, orderError, orderUpdateError or noRouteError newly in the state, or listed
// once more than before (the vehicle refused an order or update), in the vehicle's words.
struct Rejected {
  std::string error_type;
  std::string description;
  bool operator==(const Rejected&) const = default;
};

using ProgressEvent = std::variant<EdgeFinished, ActionChanged, WaitingForUpdate, RouteFinished, CancelFinished,
                                   FaultRaised, FaultCleared, BatteryChanged, Rejected>;

class ProgressTracker {
 public:
  // An order or an order update was published at `t`. A new orderId starts a new order (the
  // vehicle is taken to be at its first node); the same orderId replaces everything from the
  // stitch node on and releases what it releases from `t`.
  void order_sent(const Order& order, Time t);
  // A cancelOrder instant action with this id was published at `t`.
  void cancel_sent(const std::string& action_id, Time t);

  // What changed with this state, received at `t`.
  std::vector<ProgressEvent> observe(const State& state, Time t);

  bool in_fault() const { return fault_.has_value(); }
  bool cancel_pending() const { return cancel_id_.has_value(); }
  // The order being tracked, "" after it finished, was cancelled or dropped.
  const std::string& order_id() const { return order_id_; }

 private:
  struct EdgeInfo {
    OrderEdge edge;
    Time released_at{};
  };
  void finish_edges_up_to(std::int64_t sequence_id, Time t, std::vector<ProgressEvent>& out);
  void end_current_edge(EdgeOutcome outcome, Time t, std::vector<ProgressEvent>& out);
  void end_order();
  const EdgeInfo* next_released_edge() const;
  Time free_since(const EdgeInfo& e) const;
  void track_actions(const State& s, Time t, std::vector<ProgressEvent>& out);
  void track_faults(const State& s, Time t, std::vector<ProgressEvent>& out);
  void track_rejections(const State& s, std::vector<ProgressEvent>& out);
  void track_battery(const State& s, std::vector<ProgressEvent>& out);
  void track_route(const State& s, Time t, std::vector<ProgressEvent>& out);

  std::string order_id_;
  std::map<std::int64_t, std::string> nodes_;  // sequenceId -> nodeId
  std::map<std::int64_t, EdgeInfo> edges_;     // sequenceId -> edge, released or not
  std::int64_t last_sequence_ = 0;             // the node the vehicle last reached
  std::int64_t latest_update_id_ = 0;          // the orderUpdateId sent last
  Time arrived_at_{};
  std::int64_t waiting_reported_at_ = -1;
  bool route_finished_ = false;
  bool fault_in_current_edge_ = false;

  std::optional<std::string> cancel_id_;
  std::map<std::string, ActionStatus> actions_;
  std::optional<std::string> fault_;
  Time fault_cleared_at_{};
  std::map<std::pair<std::string, std::string>, int> rejections_;  // how often each is listed
  std::optional<BatteryChanged> battery_;
};

}  // namespace rondo::vda5050
