// The progress tracker on scripted sequences of vehicle states.
#include <gtest/gtest.h>

#include "rondo/vda5050/progress.h"

namespace rondo::vda5050 {
namespace {

Time at(int seconds) {
  return *parse_time("2026-12-01T10:00:00Z") + rondo::seconds(seconds);
}

// A line A - B - C - D, edges with sequenceIds 1, 3, 5; the first `base` edges released.
Order line_order(std::size_t base, std::int64_t update = 0) {
  Order o{.order_id = "o1", .order_update_id = update, .nodes = {}, .edges = {}};
  const char* names[] = {"A", "B", "C", "D"};
  for (std::size_t i = 0; i < 4; ++i) {
    o.nodes.push_back({.node_id = names[i],
                       .sequence_id = static_cast<std::int64_t>(2 * i),
                       .released = i <= base,
                       .position = std::nullopt,
                       .actions = {}});
  }
  for (std::size_t i = 0; i < 3; ++i) {
    o.edges.push_back({.edge_id = std::string(names[i]) + names[i + 1],
                       .sequence_id = static_cast<std::int64_t>(2 * i + 1),
                       .released = i < base,
                       .start_node_id = names[i],
                       .end_node_id = names[i + 1],
                       .max_speed = std::nullopt,
                       .length = std::nullopt,
                       .actions = {}});
  }
  return o;
}

// The vehicle's state: at node `last` (sequenceId `seq`), with the order's nodes and edges after it.
State vehicle(const Order& o, const std::string& last, std::int64_t seq, bool driving) {
  State s;
  s.order_id = o.order_id;
  s.order_update_id = o.order_update_id;
  s.last_node_id = last;
  s.last_node_sequence_id = seq;
  s.driving = driving;
  for (const OrderNode& n : o.nodes) {
    if (n.sequence_id > seq) s.node_states.push_back({n.node_id, n.sequence_id, n.released});
  }
  for (const OrderEdge& e : o.edges) {
    if (e.sequence_id > seq) s.edge_states.push_back({e.edge_id, e.sequence_id, e.released});
  }
  s.battery_state = {.battery_charge = 80, .charging = false, .battery_voltage = std::nullopt};
  return s;
}

template <class T>
std::vector<T> only(const std::vector<ProgressEvent>& events) {
  std::vector<T> out;
  for (const ProgressEvent& e : events) {
    if (const T* t = std::get_if<T>(&e)) out.push_back(*t);
  }
  return out;
}

TEST(Vda5050Progress, EdgesFinishWithTheirTimesThenWaitsForTheUpdateThenFinishes) {
  ProgressTracker p;
  Order o = line_order(2);
  p.order_sent(o, at(0));
  EXPECT_TRUE(only<EdgeFinished>(p.observe(vehicle(o, "A", 0, true), at(1))).empty());
  auto e1 = only<EdgeFinished>(p.observe(vehicle(o, "B", 2, true), at(10)));
  ASSERT_EQ(e1.size(), 1u);
  EXPECT_EQ(e1[0].attempt.edge_id, "AB");
  EXPECT_EQ(e1[0].attempt.from_node, "A");
  EXPECT_EQ(e1[0].attempt.to_node, "B");
  EXPECT_EQ(e1[0].attempt.start, at(0));
  EXPECT_EQ(e1[0].attempt.duration, seconds(10));
  EXPECT_EQ(e1[0].attempt.outcome, EdgeOutcome::kSucceeded);
  EXPECT_TRUE(e1[0].attempt.timed);
  // The same state again changes nothing.
  EXPECT_TRUE(only<EdgeFinished>(p.observe(vehicle(o, "B", 2, true), at(11))).empty());

  auto at_base_end = p.observe(vehicle(o, "C", 4, false), at(16));
  ASSERT_EQ(only<EdgeFinished>(at_base_end).size(), 1u);
  EXPECT_EQ(only<EdgeFinished>(at_base_end)[0].attempt.duration, seconds(6));
  auto waiting = only<WaitingForUpdate>(at_base_end);
  ASSERT_EQ(waiting.size(), 1u);
  EXPECT_EQ(waiting[0].node_id, "C");
  EXPECT_TRUE(only<RouteFinished>(at_base_end).empty());
  EXPECT_TRUE(only<WaitingForUpdate>(p.observe(vehicle(o, "C", 4, false), at(17))).empty());

  // The update releases the last edge at 20 s: its attempt starts then, not at the arrival.
  Order u = line_order(3, 1);
  u.nodes.erase(u.nodes.begin(), u.nodes.begin() + 2);
  u.edges.erase(u.edges.begin(), u.edges.begin() + 2);
  p.order_sent(u, at(20));
  EXPECT_TRUE(p.observe(vehicle(o, "C", 4, false), at(21)).size() == 0);  // not yet accepted
  auto done = p.observe(vehicle(u, "D", 6, false), at(27));
  auto e3 = only<EdgeFinished>(done);
  ASSERT_EQ(e3.size(), 1u);
  EXPECT_EQ(e3[0].attempt.edge_id, "CD");
  EXPECT_EQ(e3[0].attempt.start, at(20));
  EXPECT_EQ(e3[0].attempt.duration, seconds(7));
  ASSERT_EQ(only<RouteFinished>(done).size(), 1u);
  EXPECT_EQ(only<RouteFinished>(done)[0].node_id, "D");
}

TEST(Vda5050Progress, SeveralEdgesInOneStateAreNotTimed) {
  ProgressTracker p;
  Order o = line_order(3);
  p.order_sent(o, at(0));
  auto e = only<EdgeFinished>(p.observe(vehicle(o, "C", 4, true), at(12)));
  ASSERT_EQ(e.size(), 2u);
  EXPECT_FALSE(e[0].attempt.timed);
  EXPECT_FALSE(e[1].attempt.timed);
  EXPECT_EQ(e[1].attempt.edge_id, "BC");
}

TEST(Vda5050Progress, StatesOfAnotherOrderOrNodeAreNotProgress) {
  ProgressTracker p;
  Order o = line_order(3);
  p.order_sent(o, at(0));
  State other = vehicle(o, "B", 2, true);
  other.order_id = "old";
  EXPECT_TRUE(only<EdgeFinished>(p.observe(other, at(5))).empty());
  State wrong_node = vehicle(o, "C", 2, true);  // sequenceId 2 is B in this order
  EXPECT_TRUE(only<EdgeFinished>(p.observe(wrong_node, at(6))).empty());
}

TEST(Vda5050Progress, CancelIsFinishedOnlyWhenTheVehicleSaysSo) {
  ProgressTracker p;
  Order o = line_order(3);
  p.order_sent(o, at(0));
  p.observe(vehicle(o, "B", 2, true), at(10));
  p.cancel_sent("cancel-1", at(12));
  EXPECT_TRUE(p.cancel_pending());
  State running = vehicle(o, "B", 2, true);
  running.action_states = {{"cancel-1", "cancelOrder", ActionStatus::kRunning, ""}};
  auto r = p.observe(running, at(13));
  EXPECT_TRUE(only<CancelFinished>(r).empty());
  EXPECT_TRUE(only<EdgeFinished>(r).empty());
  EXPECT_EQ(only<ActionChanged>(r).size(), 1u);
  // The vehicle stops and clears the order; without FINISHED the cancel is still not done, and
  // the emptied order is not taken as a failure.
  State stopped = vehicle(o, "B", 2, false);
  stopped.node_states.clear();
  stopped.edge_states.clear();
  stopped.action_states = running.action_states;
  EXPECT_TRUE(only<EdgeFinished>(p.observe(stopped, at(14))).empty());
  EXPECT_TRUE(p.cancel_pending());
  stopped.action_states[0].action_status = ActionStatus::kFinished;
  auto done = p.observe(stopped, at(15));
  auto c = only<CancelFinished>(done);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_TRUE(c[0].succeeded);
  auto e = only<EdgeFinished>(done);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].attempt.edge_id, "BC");
  EXPECT_EQ(e[0].attempt.outcome, EdgeOutcome::kCancelled);
  EXPECT_EQ(e[0].attempt.duration, seconds(5));
  EXPECT_FALSE(p.cancel_pending());
  EXPECT_EQ(p.order_id(), "");
}

TEST(Vda5050Progress, AFailedCancelLeavesTheOrderRunning) {
  ProgressTracker p;
  Order o = line_order(3);
  p.order_sent(o, at(0));
  p.cancel_sent("c", at(1));
  State s = vehicle(o, "A", 0, true);
  s.action_states = {{"c", "cancelOrder", ActionStatus::kFailed, "busy"}};
  auto c = only<CancelFinished>(p.observe(s, at(2)));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(c[0].succeeded);
  EXPECT_EQ(c[0].result_description, "busy");
  EXPECT_EQ(p.order_id(), "o1");
}

TEST(Vda5050Progress, ADroppedOrderFailsTheEdgeItWasOn) {
  ProgressTracker p;
  Order o = line_order(3);
  p.order_sent(o, at(0));
  p.observe(vehicle(o, "B", 2, true), at(10));
  State dropped = vehicle(o, "B", 2, false);
  dropped.node_states.clear();
  dropped.edge_states.clear();
  auto e = only<EdgeFinished>(p.observe(dropped, at(18)));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].attempt.outcome, EdgeOutcome::kFailed);
  EXPECT_EQ(e[0].attempt.duration, seconds(8));
}

TEST(Vda5050Progress, FaultsRaiseAndClearAndTaintTheEdge) {
  ProgressTracker p;
  Order o = line_order(3);
  p.order_sent(o, at(0));
  State s = vehicle(o, "A", 0, true);
  s.errors = {{"batteryLowError", ErrorLevel::kFatal, "low", {}}};
  auto r = p.observe(s, at(3));
  ASSERT_EQ(only<FaultRaised>(r).size(), 1u);
  EXPECT_NE(only<FaultRaised>(r)[0].reason.find("batteryLowError"), std::string::npos);
  EXPECT_TRUE(p.in_fault());
  s.errors[0].error_level = ErrorLevel::kWarning;  // a warning is not a fault
  EXPECT_EQ(only<FaultCleared>(p.observe(s, at(5))).size(), 1u);
  s.operating_mode = OperatingMode::kManual;
  auto m = only<FaultRaised>(p.observe(s, at(6)));
  ASSERT_EQ(m.size(), 1u);
  EXPECT_NE(m[0].reason.find("MANUAL"), std::string::npos);
  s = vehicle(o, "A", 0, true);
  EXPECT_EQ(only<FaultCleared>(p.observe(s, at(8))).size(), 1u);
  // The edge during which the faults began is not learning data.
  auto e = only<EdgeFinished>(p.observe(vehicle(o, "B", 2, true), at(12)));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].attempt.outcome, EdgeOutcome::kRobotFault);
  // The next edge starts clean.
  auto e2 = only<EdgeFinished>(p.observe(vehicle(o, "C", 4, true), at(20)));
  ASSERT_EQ(e2.size(), 1u);
  EXPECT_EQ(e2[0].attempt.outcome, EdgeOutcome::kSucceeded);
  EXPECT_EQ(e2[0].attempt.duration, seconds(8));
}

TEST(Vda5050Progress, AFaultAtANodeDelaysTheNextEdgesStart) {
  ProgressTracker p;
  Order o = line_order(3);
  p.order_sent(o, at(0));
  p.observe(vehicle(o, "B", 2, false), at(10));
  State s = vehicle(o, "B", 2, false);
  s.operating_mode = OperatingMode::kService;
  p.observe(s, at(10));
  EXPECT_EQ(only<FaultCleared>(p.observe(vehicle(o, "B", 2, false), at(30))).size(), 1u);
  auto e = only<EdgeFinished>(p.observe(vehicle(o, "C", 4, true), at(36)));
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0].attempt.start, at(30));
  EXPECT_EQ(e[0].attempt.duration, seconds(6));
}

TEST(Vda5050Progress, RejectionsBatteryAndActions) {
  ProgressTracker p;
  Order o = line_order(1);
  p.order_sent(o, at(0));
  State s = vehicle(o, "A", 0, true);
  s.errors = {{"orderUpdateError", ErrorLevel::kWarning, "stitch node mismatch", {}}};
  s.action_states = {{"o1/6/0", "noop", ActionStatus::kWaiting, ""}};
  auto r = p.observe(s, at(1));
  ASSERT_EQ(only<Rejected>(r).size(), 1u);
  EXPECT_EQ(only<Rejected>(r)[0].description, "stitch node mismatch");
  EXPECT_EQ(only<BatteryChanged>(r).size(), 1u);
  EXPECT_EQ(only<ActionChanged>(r).size(), 1u);
  EXPECT_FALSE(p.in_fault());  // a rejection is a warning, not a fault
  s.battery_state.battery_charge = 80.4;
  s.action_states[0].action_status = ActionStatus::kFinished;
  auto r2 = p.observe(s, at(2));
  EXPECT_TRUE(only<Rejected>(r2).empty());        // the same rejection is reported once
  EXPECT_TRUE(only<BatteryChanged>(r2).empty());  // nor a change below one percent
  ASSERT_EQ(only<ActionChanged>(r2).size(), 1u);
  EXPECT_EQ(only<ActionChanged>(r2)[0].status, ActionStatus::kFinished);
  s.battery_state.charging = true;
  EXPECT_EQ(only<BatteryChanged>(p.observe(s, at(3))).size(), 1u);
}

// A vehicle that rejects the same order twice lists the same error twice (vda-5050-lib appends
// each rejection): the second one is news too.
TEST(Vda5050Progress, TheSameRejectionAgainIsReportedAgain) {
  ProgressTracker p;
  Order o = line_order(1);
  p.order_sent(o, at(0));
  State s = vehicle(o, "A", 0, true);
  const VehicleError e{"orderError", ErrorLevel::kWarning, "order action is not executable", {}};
  s.errors = {e};
  EXPECT_EQ(only<Rejected>(p.observe(s, at(1))).size(), 1u);
  EXPECT_TRUE(only<Rejected>(p.observe(s, at(2))).empty());
  s.errors = {e, e};
  EXPECT_EQ(only<Rejected>(p.observe(s, at(3))).size(), 1u);
  s.errors = {};
  EXPECT_TRUE(only<Rejected>(p.observe(s, at(4))).empty());
  s.errors = {e};
  EXPECT_EQ(only<Rejected>(p.observe(s, at(5))).size(), 1u);  // gone and back
}

}  // namespace
}  // namespace rondo::vda5050
