// Vda5050Robot's commands: drive() and run_action() as orders and order updates, cancel() as the
// cancelOrder instant action, and how the vehicle's progress answers them.
#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "robot_impl.h"
#include "rondo/map/map_geometry.h"
#include "rondo/vda5050/encode.h"
#include "rondo/vda5050/order_builder.h"

namespace rondo::vda5050 {
namespace {

// Beyond this distance from its first node, a new order widens the node's deviation range to
// take the vehicle where it stands (e.g. stopped in the middle of an edge by a cancel).
constexpr double kOnNode = 0.25;  // metres

}  // namespace

// The vehicle stands at the end of the base of our last order, which it still holds: the next
// command is an update stitched there.
bool Vda5050Robot::Impl::can_stitch_at(map::NodeIndex node) const {
  if (!order || !last_state || order->nodes.empty()) return false;
  const OrderNode& end = last_base_node(*order);
  return progress.order_id() == order->order_id && last_state->order_id == order->order_id &&
         end.node_id == map.node(node).name && last_state->last_node_id == end.node_id &&
         last_state->last_node_sequence_id == end.sequence_id;
}

Result<Order> Vda5050Robot::Impl::order_from(map::NodeIndex start, RouteSpec spec) {
  spec.map_id = config.map_id;
  Order o;
  if (can_stitch_at(start)) {
    RONDO_ASSIGN_OR_RETURN(o, build_update(map, *order, spec));
  } else {
    RONDO_ASSIGN_OR_RETURN(o, build_order(map, fmt::format("{}-{}", order_prefix, ++order_count), spec));
    // The vehicle starts where it stands: no heading asked for, and where it is counts as the
    // first node even off it (after a cancel in the middle of an edge).
    if (OrderNode& first = o.nodes.front(); first.position) {
      first.position->theta.reset();
      if (agv_position && agv_position->map_id == config.map_id) {
        const double d = std::hypot(agv_position->x - first.position->x, agv_position->y - first.position->y);
        if (d > kOnNode) first.position->allowed_deviation_xy = std::max(first.position->allowed_deviation_xy, d + kOnNode);
      }
    }
  }
  // Action ids unique over the whole order, updates included (the builder's repeat at the stitch node).
  OrderNode& last = o.nodes.back();
  for (std::size_t i = 0; i < last.actions.size(); ++i) {
    last.actions[i].action_id = fmt::format("{}/{}/{}/{}", o.order_id, last.sequence_id, o.order_update_id, i);
  }
  return o;
}

Status Vda5050Robot::Impl::send_order(const Order& o) {
  const Json j = encode_order(headers.next(Topic::kOrder, wall_now()), o, config.compat);
  RONDO_RETURN_IF_ERROR(publish(Topic::kOrder, j));
  progress_before = progress;
  before_pending = order;
  order = o;
  progress.order_sent(o, clock.now());
  return Status{};
}

void Vda5050Robot::Impl::drive(const exec::Route& route) {
  if (!std::holds_alternative<std::monostate>(job) || ending > 0) throw std::logic_error("Vda5050Robot::drive while busy");
  if (route.edges.empty() || route.committed < 1 || route.committed > route.edges.size() ||
      map.from_index(route.edges.front()) != location) {
    throw std::logic_error("Vda5050Robot::drive: the route does not leave the robot's node");
  }
  RouteSpec spec{.route = {location}, .base_edges = route.committed, .map_id = config.map_id, .final_actions = {}};
  for (map::EdgeIndex e : route.edges) spec.route.push_back(map.to_index(e));
  job = DriveJob{.committed = {route.edges.begin(), route.edges.begin() + static_cast<std::ptrdiff_t>(route.committed)},
                 .next = 0,
                 .current_since = clock.now()};
  if (reported_fault) return end_job(reported_fault->message);
  Result<Order> o = order_from(location, spec);
  if (!o) return end_job("no order for this route: " + o.error().message);
  if (Status sent = send_order(*o); !sent) return end_job("the order was not sent: " + sent.error().message);
}

void Vda5050Robot::Impl::run_action(const rondo::Action& action, Duration) {
  if (!std::holds_alternative<std::monostate>(job) || ending > 0) throw std::logic_error("Vda5050Robot::run_action while busy");
  job = ActionJob{.name = action.name, .action_id = "", .sent = clock.now(), .started = std::nullopt};
  if (reported_fault) return end_job(reported_fault->message);
  Result<Order> o = order_from(location, {.route = {location}, .base_edges = 0, .map_id = config.map_id,
                                          .final_actions = {action}});
  if (!o) return end_job("no order for this action: " + o.error().message);
  std::get<ActionJob>(job).action_id = o->nodes.back().actions.at(0).action_id;
  if (Status sent = send_order(*o); !sent) return end_job("the order was not sent: " + sent.error().message);
}

void Vda5050Robot::Impl::cancel() {
  if (std::holds_alternative<std::monostate>(job) || cancel_id) return;
  const std::string id = fmt::format("{}-cancel-{}", order_prefix, ++instant_count);
  const Json j = encode_instant_actions(headers.next(Topic::kInstantActions, wall_now()),
                                        InstantActions{.actions = {cancel_order_action(id)}}, config.compat);
  // Not sent (rondo is off the broker): the connection fault ends what runs.
  if (!publish(Topic::kInstantActions, j)) return;
  cancel_id = id;
  progress.cancel_sent(id, clock.now());
}

void Vda5050Robot::Impl::finish_edge(const exec::EdgeAttempt& attempt) {
  auto& d = std::get<DriveJob>(job);
  ++d.next;
  d.current_since = clock.now();
  const bool last = d.next >= d.committed.size() || attempt.outcome != exec::EdgeOutcome::kSucceeded;
  if (last) job = std::monostate{};
  deliver([attempt](exec::RobotListener& l) { l.on_edge_finished(attempt); }, last);
}

void Vda5050Robot::Impl::finish_action(exec::ActionOutcome outcome, const std::string& message) {
  const ActionJob a = std::get<ActionJob>(job);
  job = std::monostate{};
  const Time start = a.started.value_or(a.sent);
  exec::ActionResult r{
      .name = a.name, .start = start, .duration = clock.now() - start, .outcome = outcome, .message = message};
  deliver([r](exec::RobotListener& l) { l.on_action_finished(r); }, true);
}

// A fault (or a command that could not be sent) ends what runs as a robot fault.
void Vda5050Robot::Impl::end_job(const std::string& message) {
  if (auto* d = std::get_if<DriveJob>(&job)) {
    const Time since = d->current_since;
    finish_edge({.edge = d->committed[d->next],
                 .start = since,
                 .duration = clock.now() - since,
                 .outcome = exec::EdgeOutcome::kRobotFault,
                 .message = message});
  } else if (std::holds_alternative<ActionJob>(job)) {
    finish_action(exec::ActionOutcome::kRobotFault, message);
  }
}

void Vda5050Robot::Impl::rejected(const Rejected& r) {
  const std::string words = fmt::format("{}: {}", r.error_type, r.description);
  const bool ours = !std::holds_alternative<std::monostate>(job) && order.has_value();
  if (!ours) return ignore("the vehicle reports a rejection: " + words);
  const std::string what = fmt::format("the vehicle rejected order {} update {}: {}", order->order_id,
                                       order->order_update_id, words);
  // It still holds what it had: go on from there.
  order = before_pending;
  if (progress_before) {
    progress = *progress_before;
    progress_before.reset();
  }
  if (std::holds_alternative<ActionJob>(job)) return finish_action(exec::ActionOutcome::kFailed, what);
  // A rejected drive: a fault for a while, then the executor tries again from where the vehicle is.
  rejected_fault = what;
  if (retry_timer != 0) clock.cancel(retry_timer);
  retry_timer = clock.schedule_after(options.retry_rejected_after, [this] {
    retry_timer = 0;
    rejected_fault.reset();
    update_faults();
  });
  update_faults();
}

void Vda5050Robot::Impl::handle(const ProgressEvent& event) {
  if (const auto* f = std::get_if<EdgeFinished>(&event)) {
    const EdgeAttempt& a = f->attempt;
    const std::optional<map::EdgeIndex> e = map.find_edge(a.edge_id);
    if (!e) return ignore(fmt::format("state: edge '{}' is not on map '{}'", a.edge_id, map.name()));
    if (a.outcome == EdgeOutcome::kSucceeded) distance_m += map::edge_length(map, *e);
    auto* d = std::get_if<DriveJob>(&job);
    if (d == nullptr || d->committed[d->next] != *e) return;  // the vehicle went on while rondo was not there
    exec::EdgeAttempt x{
        .edge = *e, .start = a.start, .duration = a.duration, .outcome = a.outcome, .message = ""};
    if (a.outcome == EdgeOutcome::kSucceeded && !a.timed) {
      // Passed with others between two states: where it lies in time is unknown, not learning data.
      x.outcome = exec::EdgeOutcome::kRobotFault;
      x.message = "passed between two state messages: not timed";
    }
    if (a.outcome == EdgeOutcome::kFailed) x.message = "the vehicle dropped the order with this edge ahead";
    if (a.outcome == EdgeOutcome::kCancelled) {
      x.message = fmt::format("the vehicle reported cancelOrder {} FINISHED", cancel_id.value_or("?"));
    }
    return finish_edge(x);
  }
  if (const auto* a = std::get_if<ActionChanged>(&event)) {
    auto* j = std::get_if<ActionJob>(&job);
    if (j == nullptr || j->action_id != a->action_id) return;
    if ((a->status == ActionStatus::kInitializing || a->status == ActionStatus::kRunning) && !j->started) {
      j->started = clock.now();
    }
    if (a->status == ActionStatus::kFinished) return finish_action(exec::ActionOutcome::kSucceeded, a->result_description);
    if (a->status == ActionStatus::kFailed) {
      return finish_action(cancel_id ? exec::ActionOutcome::kCancelled : exec::ActionOutcome::kFailed,
                           a->result_description);
    }
    return;
  }
  if (const auto* c = std::get_if<CancelFinished>(&event)) {
    if (!cancel_id || c->action_id != *cancel_id) return;
    cancel_id.reset();
    if (!c->succeeded) return;  // nothing was cancelled: what runs goes on
    // The vehicle stopped: what still runs (the tracker ended a started edge already) is cancelled.
    if (auto* d = std::get_if<DriveJob>(&job)) {
      return finish_edge({.edge = d->committed[d->next],
                          .start = d->current_since,
                          .duration = clock.now() - d->current_since,
                          .outcome = exec::EdgeOutcome::kCancelled,
                          .message = fmt::format("the vehicle reported cancelOrder {} FINISHED", c->action_id)});
    }
    if (std::holds_alternative<ActionJob>(job)) finish_action(exec::ActionOutcome::kCancelled, c->result_description);
    return;
  }
  if (const auto* b = std::get_if<BatteryChanged>(&event)) {
    battery = std::clamp(b->charge / 100.0, 0.0, 1.0);
    charging = b->charging;
    return;
  }
  if (const auto* r = std::get_if<Rejected>(&event)) return rejected(*r);
}

}  // namespace rondo::vda5050
