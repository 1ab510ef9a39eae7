// Vda5050Robot's side of the robot contract (exec/robot.h) that needs no vehicle: bad
// configuration is an error, a vehicle not heard from is a fault, and while in fault every
// command is answered with a robot fault, always from the clock, never from inside the call.
// (Against a real vehicle: gtest_vda5050_day.)
#include <gtest/gtest.h>

#include <vector>

#include "rondo/exec/clock.h"
#include "rondo/map/map_loader.h"
#include "rondo/vda5050/vda5050_robot.h"

namespace rondo::vda5050 {
namespace {

struct Recorder final : exec::RobotListener {
  std::vector<exec::EdgeAttempt> edges;
  std::vector<exec::ActionResult> actions;
  std::vector<exec::RobotFault> faults;
  int ready = 0;
  void on_edge_finished(const exec::EdgeAttempt& a) override { edges.push_back(a); }
  void on_action_finished(const exec::ActionResult& r) override { actions.push_back(r); }
  void on_interruptible_changed(bool) override {}
  void on_observation(const exec::Observation&) override {}
  void on_fault(const exec::RobotFault& f) override { faults.push_back(f); }
  void on_ready() override { ++ready; }
};

Vda5050Config config() {
  // Port 1 on loopback: nothing listens, the client keeps retrying in the background.
  return {.broker = "mqtt://127.0.0.1:1",
          .topics = {.interface_name = "uagv", .manufacturer = "acme", .serial_number = "agv-7"},
          .map_id = "g4s_y2",
          .offline_after = seconds(30),
          .compat = {}};
}

TEST(Vda5050Robot, BadConfigurationIsAnError) {
  auto map = map::load_map("examples/g4s/map.yaml");
  ASSERT_TRUE(map.ok());
  exec::SimClock clock(Time{});
  Vda5050Config bad = config();
  bad.broker = "http://127.0.0.1:1883";
  EXPECT_FALSE(Vda5050Robot::create(clock, *map, bad, {}).ok());
  bad = config();
  bad.topics.serial_number = "agv/7";
  EXPECT_FALSE(Vda5050Robot::create(clock, *map, bad, {}).ok());
  EXPECT_FALSE(Vda5050Robot::create(clock, *map, config(), {.start = map->node_count()}).ok());
}

TEST(Vda5050Robot, UnheardItIsAFaultAndEveryCommandEndsAsARobotFaultFromTheClock) {
  auto map = map::load_map("examples/g4s/map.yaml");
  ASSERT_TRUE(map.ok());
  exec::SimClock clock(Time{});
  const map::NodeIndex dock = *map->find_node("ChargingPoint");
  auto robot = Vda5050Robot::create(clock, *map, config(), {.start = dock});
  ASSERT_TRUE(robot.ok()) << robot.error().message;
  Recorder listener;
  (*robot)->set_listener(&listener);
  ASSERT_TRUE((*robot)->activate().ok());
  EXPECT_TRUE(listener.faults.empty());  // never from inside the call
  ASSERT_TRUE(clock.step());
  ASSERT_EQ(listener.faults.size(), 1u);
  EXPECT_EQ(listener.faults[0].kind, exec::RobotFault::Kind::kConnectionLost);
  EXPECT_NE(listener.faults[0].message.find("agv-7"), std::string::npos) << listener.faults[0].message;
  ASSERT_TRUE((*robot)->fault().has_value());
  EXPECT_EQ((*robot)->location(), dock);
  EXPECT_EQ((*robot)->position(), map->node(dock).pose);

  const map::EdgeIndex out = map->out_edges(dock)[0];
  (*robot)->drive({.edges = {out}, .committed = 1});
  EXPECT_TRUE(listener.edges.empty());
  EXPECT_TRUE((*robot)->busy());  // until the callback is delivered
  ASSERT_TRUE(clock.step());
  EXPECT_FALSE((*robot)->busy());
  ASSERT_EQ(listener.edges.size(), 1u);
  EXPECT_EQ(listener.edges[0].edge, out);
  EXPECT_EQ(listener.edges[0].outcome, exec::EdgeOutcome::kRobotFault);
  EXPECT_FALSE(exec::is_learning_data(listener.edges[0].outcome));

  (*robot)->run_action(Action{"noop", {{"duration", "2"}}}, seconds(2));
  EXPECT_TRUE(listener.actions.empty());
  ASSERT_TRUE(clock.step());
  ASSERT_EQ(listener.actions.size(), 1u);
  EXPECT_EQ(listener.actions[0].name, "noop");
  EXPECT_EQ(listener.actions[0].outcome, exec::ActionOutcome::kRobotFault);
  (*robot)->cancel();  // idle: nothing happens
  clock.run_until(clock.now() + minutes(1));  // the silence checks: still the same fault
  EXPECT_EQ(listener.ready, 0);
  EXPECT_TRUE(listener.edges.size() == 1 && listener.actions.size() == 1);
  (*robot)->deactivate();
}

}  // namespace
}  // namespace rondo::vda5050
