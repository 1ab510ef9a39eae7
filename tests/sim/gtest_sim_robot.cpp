#include "rondo/sim/sim_robot.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "rondo/exec/clock.h"
#include "rondo/map/map_geometry.h"
#include "rondo/sim/parametric_world.h"
#include "sim_test_util.h"

namespace rondo::sim {
namespace {

using namespace rondo::sim::testing;

// Records everything the robot says, with the clock's time, and whether it came from inside a
// call to the robot (which the contract forbids).
class Recorder final : public exec::RobotListener {
 public:
  explicit Recorder(exec::Clock& clock) : clock_(clock) {}
  void on_edge_finished(const exec::EdgeAttempt& a) override {
    edges.push_back(a);
    log("edge " + std::string(a.succeeded() ? "ok" : exec::to_string(a.outcome)));
    if (then) std::exchange(then, nullptr)();
  }
  void on_action_finished(const exec::ActionResult& r) override {
    actions.push_back(r);
    log(std::string("action ") + exec::to_string(r.outcome));
  }
  void on_interruptible_changed(bool interruptible) override {
    log(interruptible ? "interruptible" : "not interruptible");
  }
  void on_observation(const exec::Observation& o) override {
    observations.push_back(o);
    log("saw " + o.where + (o.value > 0.5 ? " open" : " closed"));
  }
  void on_fault(const exec::RobotFault& f) override { log("fault " + f.message); }
  void on_ready() override { log("ready"); }
  void log(const std::string& what) {
    events.push_back({clock_.now(), what});
    if (inside_call) ++calls_from_inside;
  }

  std::vector<exec::EdgeAttempt> edges;
  std::vector<exec::ActionResult> actions;
  std::vector<exec::Observation> observations;
  std::vector<std::pair<Time, std::string>> events;
  bool inside_call = false;
  int calls_from_inside = 0;
  std::function<void()> then;  // runs once inside the next edge callback

 private:
  exec::Clock& clock_;
};

const Time kStart = parse_time("2026-11-23T10:00:00Z").value();  // a Monday morning, UTC+0 in London

// Exact durations (no noise), no random failures unless asked; Office_Hall always fails.
SimWorld exact_world(const map::TopoMap& m, double failure_probability = 0.0) {
  ParametricSpec spec;
  spec.failure_probability = failure_probability;
  spec.noise = {.sigma = 0, .tail_probability = 0};
  spec.failed = {.min_factor = 0.5, .max_factor = 0.5};
  spec.effects.push_back({.name = "blocked", .edges = {edge(m, "Office_Hall")}, .closed = true});
  SimWorld w;
  w.edges = std::make_unique<ParametricWorld>(m, london(), spec);
  w.actions = ActionModel({.sigma = 0, .failure_probability = 0, .overrun_probability = 0},
                          {{"talk", {.sigma = 0, .failure_probability = 0, .overrun_probability = 0,
                                     .non_interruptible = minutes(2)}}});
  w.battery = {.initial = 0.5, .moving_per_hour = 0.6, .acting_per_hour = 0.3, .charging_per_hour = 0.6};
  return w;
}

struct Fixture {
  map::TopoMap m = small_map();
  SimWorld world = exact_world(m);
  exec::SimClock clock{kStart};
  Recorder rec{clock};
  SimRobot robot{clock, m, world, {.start = node(m, "Dock"), .dock = node(m, "Dock"), .seed = 3}};
  Fixture() { robot.set_listener(&rec); }
  void traverse(const char* id) {
    rec.inside_call = true;
    robot.traverse(edge(m, id));
    rec.inside_call = false;
  }
  void act(const char* name, Duration expected) {
    rec.inside_call = true;
    robot.run_action(Action{name, {}}, expected);
    rec.inside_call = false;
  }
  // Waits until the robot is free, then runs the action and waits for it.
  void act_after_idle(const char* name, Duration expected) {
    clock.run_until(clock.now() + hours(1));
    act(name, expected);
    clock.run_until(clock.now() + hours(1));
  }
  void cancel() {
    rec.inside_call = true;
    robot.cancel();
    rec.inside_call = false;
  }
};

TEST(SimRobot, ARouteDrivesItsCommittedEdgesAndStopsBeforeTheHorizon) {
  Fixture f;
  f.robot.drive({.edges = {edge(f.m, "Dock_Hall"), edge(f.m, "Hall_Office"), edge(f.m, "Office_Hall")},
                 .committed = 2});
  std::vector<bool> busy_in_callback;
  f.rec.then = [&] {
    busy_in_callback.push_back(f.robot.busy());
    f.rec.then = [&] { busy_in_callback.push_back(f.robot.busy()); };
  };
  f.clock.run_until(kStart + hours(1));
  ASSERT_EQ(f.rec.edges.size(), 2u);  // the horizon edge is not driven
  EXPECT_EQ(f.rec.edges[0].edge, edge(f.m, "Dock_Hall"));
  EXPECT_EQ(f.rec.edges[1].edge, edge(f.m, "Hall_Office"));
  EXPECT_EQ(f.rec.edges[1].start, f.rec.edges[0].start + f.rec.edges[0].duration);
  EXPECT_EQ(busy_in_callback, (std::vector<bool>{true, false}));  // busy until the last committed edge
  EXPECT_EQ(f.robot.location(), node(f.m, "Office"));
  EXPECT_FALSE(f.robot.busy());
  EXPECT_THROW(f.robot.drive({.edges = {edge(f.m, "Office_Hall")}, .committed = 2}), std::logic_error);
  EXPECT_THROW(f.robot.drive({.edges = {edge(f.m, "Office_Hall"), edge(f.m, "Dock_Hall")}, .committed = 1}),
               std::logic_error);  // not consecutive
}

TEST(SimRobot, AFailedEdgeEndsTheDrive) {
  Fixture f;
  f.robot.drive({.edges = {edge(f.m, "Dock_Hall"), edge(f.m, "Hall_Office")}, .committed = 2});
  f.clock.run_until(kStart + hours(1));
  f.robot.drive({.edges = {edge(f.m, "Office_Hall"), edge(f.m, "Hall_Dock")}, .committed = 2});  // Office_Hall is closed
  f.clock.run_until(kStart + hours(2));
  ASSERT_EQ(f.rec.edges.size(), 3u);
  EXPECT_EQ(f.rec.edges[2].outcome, exec::EdgeOutcome::kFailed);
  EXPECT_EQ(f.robot.location(), node(f.m, "Office"));
  EXPECT_FALSE(f.robot.busy());
}

TEST(SimRobot, TheDoorSensorSeesDoorsInRangeAsTheWorldHasThemAndMissesSome) {
  Fixture f;
  f.world.door_sensor = {.enabled = true, .range_m = 5.0, .miss_rate = 0.0};
  SimRobot robot(f.clock, f.m, f.world, {.start = node(f.m, "Dock"), .dock = node(f.m, "Dock"), .seed = 3});
  robot.set_listener(&f.rec);
  robot.traverse(edge(f.m, "Dock_Hall"));  // Hall is an end of the door's edges: in range
  f.clock.run_until(kStart + hours(1));
  ASSERT_EQ(f.rec.observations.size(), 1u);
  EXPECT_EQ(f.rec.observations[0].what, "door_open");
  EXPECT_EQ(f.rec.observations[0].where, "kd");
  EXPECT_EQ(f.rec.observations[0].value, 1.0);
  EXPECT_EQ(f.rec.observations[0].when, f.rec.edges[0].start + f.rec.edges[0].duration);
  // The observation comes before the edge's callback.
  const auto saw = std::find_if(f.rec.events.begin(), f.rec.events.end(), [](const auto& e) { return e.second == "saw kd open"; });
  const auto edge_done = std::find_if(f.rec.events.begin(), f.rec.events.end(), [](const auto& e) { return e.second == "edge ok"; });
  EXPECT_LT(saw, edge_done);
  robot.traverse(edge(f.m, "Hall_Office"));  // Office is 10 m from both ends of the door: out of range
  f.clock.run_until(kStart + hours(2));
  EXPECT_EQ(f.rec.observations.size(), 1u);

  // A door the building has closed is seen closed.
  ParametricSpec closed;
  closed.effects.push_back({.name = "kitchen shut", .edges = {edge(f.m, "Hall_Kitchen"), edge(f.m, "Kitchen_Hall")},
                            .closed = true});
  SimWorld shut;
  shut.edges = std::make_unique<ParametricWorld>(f.m, london(), closed);
  shut.door_sensor = f.world.door_sensor;
  Recorder rec(f.clock);
  SimRobot other(f.clock, f.m, shut, {.start = node(f.m, "Dock"), .dock = node(f.m, "Dock"), .seed = 3});
  other.set_listener(&rec);
  other.traverse(edge(f.m, "Dock_Hall"));
  f.clock.run_until(kStart + hours(3));
  ASSERT_EQ(rec.observations.size(), 1u);
  EXPECT_EQ(rec.observations[0].value, 0.0);

  // A sensor that always misses sees nothing, and the other draws of the run are unchanged.
  Fixture g;
  g.world.door_sensor = {.enabled = true, .range_m = 5.0, .miss_rate = 1.0};
  SimRobot blind(g.clock, g.m, g.world, {.start = node(g.m, "Dock"), .dock = node(g.m, "Dock"), .seed = 3});
  blind.set_listener(&g.rec);
  blind.traverse(edge(g.m, "Dock_Hall"));
  g.clock.run_until(kStart + hours(1));
  EXPECT_TRUE(g.rec.observations.empty());
  ASSERT_EQ(g.rec.edges.size(), 1u);
  EXPECT_EQ(g.rec.edges[0].duration, f.rec.edges[0].duration);
}

TEST(SimRobot, AFaultEndsTheRunningEdgeAsARobotFaultAndCommandsFailUntilReady) {
  Fixture f;
  f.traverse("Dock_Hall");
  f.clock.run_until(kStart + seconds(5));
  f.robot.inject_fault({.kind = exec::RobotFault::Kind::kConnectionLost, .message = "link down"});
  f.clock.run_until(kStart + seconds(6));
  ASSERT_EQ(f.rec.edges.size(), 1u);
  EXPECT_EQ(f.rec.edges[0].outcome, exec::EdgeOutcome::kRobotFault);
  EXPECT_EQ(f.rec.edges[0].duration, seconds(5));
  EXPECT_EQ(f.robot.location(), node(f.m, "Dock"));
  ASSERT_TRUE(f.robot.fault());
  EXPECT_EQ(f.robot.fault()->message, "link down");
  f.act("talk", minutes(1));
  f.clock.run_until(kStart + seconds(7));
  ASSERT_EQ(f.rec.actions.size(), 1u);
  EXPECT_EQ(f.rec.actions[0].outcome, exec::ActionOutcome::kRobotFault);
  f.robot.clear_fault();
  f.clock.run_until(kStart + seconds(8));
  EXPECT_FALSE(f.robot.fault());
  EXPECT_EQ(f.rec.events.back().second, "ready");
  EXPECT_EQ(f.rec.calls_from_inside, 0);
  f.traverse("Dock_Hall");
  f.clock.run_until(kStart + hours(1));
  EXPECT_TRUE(f.rec.edges.back().succeeded());
}

TEST(SimRobot, AnEdgeIsAnsweredOnceLaterFromTheClock) {
  Fixture f;
  f.traverse("Dock_Hall");
  EXPECT_TRUE(f.robot.busy());
  EXPECT_TRUE(f.rec.edges.empty());
  EXPECT_EQ(f.robot.location(), node(f.m, "Dock"));  // while crossing: the node it left
  f.clock.run_until(kStart + hours(1));
  ASSERT_EQ(f.rec.edges.size(), 1u);
  EXPECT_EQ(f.rec.calls_from_inside, 0);
  const auto& a = f.rec.edges[0];
  EXPECT_TRUE(a.succeeded());
  EXPECT_EQ(a.start, kStart);
  EXPECT_EQ(a.duration, seconds(52) + milliseconds(222));  // 10 m at 0.45 m/s + 30 s undocking
  EXPECT_EQ(f.rec.events[0].first, kStart + a.duration);
  EXPECT_FALSE(f.robot.busy());
  EXPECT_EQ(f.robot.location(), node(f.m, "Hall"));
  EXPECT_DOUBLE_EQ(f.robot.distance_m(), 10.0);
}

TEST(SimRobot, AFailedEdgeLeavesTheRobotWhereItStarted) {
  Fixture f;
  f.traverse("Dock_Hall");
  f.clock.run_until(kStart + minutes(5));
  f.traverse("Hall_Office");
  f.clock.run_until(kStart + minutes(10));
  f.traverse("Office_Hall");  // closed
  f.clock.run_until(kStart + minutes(15));
  ASSERT_EQ(f.rec.edges.size(), 3u);
  EXPECT_FALSE(f.rec.edges[2].succeeded());
  EXPECT_EQ(f.rec.edges[2].outcome, exec::EdgeOutcome::kFailed);
  EXPECT_EQ(f.rec.edges[2].duration, seconds(11) + milliseconds(111));  // half of 22.222 s
  EXPECT_EQ(f.robot.location(), node(f.m, "Office"));
  EXPECT_DOUBLE_EQ(f.robot.distance_m(), 20.0);  // the failed attempt counts nothing
}

TEST(SimRobot, CancelDeliversOneCancelledResultThroughTheClock) {
  Fixture f;
  f.cancel();  // idle: nothing happens
  f.traverse("Dock_Hall");
  f.clock.run_until(kStart + seconds(5));
  f.cancel();
  f.cancel();  // twice is harmless
  EXPECT_TRUE(f.rec.edges.empty());
  EXPECT_TRUE(f.robot.busy());
  f.clock.run_until(kStart + hours(1));
  ASSERT_EQ(f.rec.edges.size(), 1u);  // the cancelled finish timer never fires
  EXPECT_EQ(f.rec.edges[0].outcome, exec::EdgeOutcome::kCancelled);
  EXPECT_FALSE(f.rec.edges[0].succeeded());
  EXPECT_EQ(f.rec.edges[0].duration, seconds(5));
  EXPECT_EQ(f.rec.events[0].first, kStart + seconds(5));
  EXPECT_EQ(f.robot.location(), node(f.m, "Dock"));
  EXPECT_EQ(f.rec.calls_from_inside, 0);
  EXPECT_FALSE(f.robot.busy());
}

TEST(SimRobot, TheListenerMayStartTheNextEdgeInsideTheCallback) {
  Fixture f;
  f.rec.then = [&] { f.robot.traverse(edge(f.m, "Hall_Office")); };
  f.traverse("Dock_Hall");
  f.clock.run_until(kStart + hours(1));
  ASSERT_EQ(f.rec.edges.size(), 2u);
  EXPECT_EQ(f.robot.location(), node(f.m, "Office"));
}

TEST(SimRobot, ANonInterruptibleActionSaysSoAtItsStartAndWhenTheSpanEnds) {
  Fixture f;
  f.act("talk", minutes(5));
  EXPECT_TRUE(f.rec.events.empty());
  f.clock.run_until(kStart + hours(1));
  const std::vector<std::pair<Time, std::string>> expected = {{kStart, "not interruptible"},
                                                              {kStart + minutes(2), "interruptible"},
                                                              {kStart + minutes(5), "action succeeded"}};
  EXPECT_EQ(f.rec.events, expected);
  ASSERT_EQ(f.rec.actions.size(), 1u);
  EXPECT_EQ(f.rec.actions[0].name, "talk");
  EXPECT_EQ(f.rec.actions[0].duration, minutes(5));
}

TEST(SimRobot, APersonsConfirmationTakesThePlacesTimeWhateverTheExecutorExpects) {
  Fixture f;
  f.world.confirmation = {.actions = {"load"}, .fallback = std::nullopt, .places = {{"Dock", minutes(3)}}};
  f.act("load", minutes(1));      // at the Dock: its person takes 3 minutes
  f.act_after_idle("talk", minutes(1));  // not a confirmed action: as expected
  ASSERT_EQ(f.rec.actions.size(), 2u);
  EXPECT_EQ(f.rec.actions[0].duration, minutes(3));
  EXPECT_EQ(f.rec.actions[1].duration, minutes(1));
  EXPECT_EQ(f.world.confirmation.at("load", "Hall"), std::nullopt);  // no default: the executor's
}

TEST(SimRobot, CancellingDuringTheSpanEndsItBeforeTheCancelledResult) {
  Fixture f;
  f.act("talk", minutes(5));
  f.clock.run_until(kStart + minutes(1));
  f.cancel();
  f.clock.run_until(kStart + hours(1));
  const std::vector<std::pair<Time, std::string>> expected = {{kStart, "not interruptible"},
                                                              {kStart + minutes(1), "interruptible"},
                                                              {kStart + minutes(1), "action cancelled"}};
  EXPECT_EQ(f.rec.events, expected);
  EXPECT_EQ(f.rec.calls_from_inside, 0);
}

TEST(SimRobot, OtherActionsNeverSayTheyAreNotInterruptible) {
  Fixture f;
  f.act("look", minutes(3));
  f.clock.run_until(kStart + hours(1));
  const std::vector<std::pair<Time, std::string>> expected = {{kStart + minutes(3), "action succeeded"}};
  EXPECT_EQ(f.rec.events, expected);
}

TEST(SimRobot, TheBatteryDrainsWhenBusyAndChargesOnlyIdleAtTheDock) {
  Fixture f;  // starts at the dock with 0.5
  EXPECT_TRUE(f.robot.charging());
  f.clock.run_until(kStart + minutes(30));  // +0.3
  EXPECT_NEAR(f.robot.battery(), 0.8, 1e-9);
  EXPECT_EQ(f.robot.charging_time(), minutes(30));
  f.traverse("Dock_Hall");
  EXPECT_FALSE(f.robot.charging());
  f.clock.run_until(kStart + hours(1));
  EXPECT_FALSE(f.robot.charging());  // at Hall
  EXPECT_NEAR(f.robot.battery(), 0.8 - 0.6 * (52.222 / 3600), 1e-6);
  f.act("look", minutes(30));  // -0.15
  f.clock.run_until(kStart + hours(2));
  EXPECT_NEAR(f.robot.battery(), 0.8 - 0.6 * (52.222 / 3600) - 0.15, 1e-6);
  EXPECT_EQ(f.robot.charging_time(), minutes(30));
}

TEST(SimRobot, TheBatteryDrainsByTheMetreOfEachEdgeCrossedOnTopOfTheHour) {
  Fixture f;
  f.world.battery.per_metre = 0.001;
  f.world.battery.charging_per_hour = 0;
  const double metres = map::edge_length(f.m, edge(f.m, "Dock_Hall"));
  f.traverse("Dock_Hall");
  f.clock.run_until(kStart + hours(1));
  EXPECT_NEAR(f.robot.battery(), 0.5 - 0.6 * (52.222 / 3600) - 0.001 * metres, 1e-6);
  f.traverse("Hall_Office");
  f.clock.run_until(kStart + hours(2));
  // A failed attempt ends where it began: time, but no metres.
  const double before = f.robot.battery();
  f.traverse("Office_Hall");  // always fails
  f.clock.run_until(kStart + hours(3));
  ASSERT_EQ(f.rec.edges.size(), 3u);
  EXPECT_FALSE(f.rec.edges[2].succeeded());
  EXPECT_NEAR(f.robot.battery(), before - 0.6 * to_seconds(f.rec.edges[2].duration) / 3600, 1e-9);
}

TEST(SimRobot, AStrandedEmptyRobotIsCarriedBackToTheDockWhenTheWorldSaysSo) {
  Fixture f;
  f.world.battery.initial = 0.0;
  f.world.battery.rescue_after = hours(1);
  SimRobot robot(f.clock, f.m, f.world, {.start = node(f.m, "Hall"), .dock = node(f.m, "Dock")});
  robot.set_listener(&f.rec);
  robot.traverse(edge(f.m, "Hall_Office"));  // empty: fails at once, and the hour starts
  f.clock.run_until(kStart + minutes(59));
  robot.traverse(edge(f.m, "Hall_Office"));
  f.clock.run_until(kStart + minutes(61));
  EXPECT_EQ(robot.location(), node(f.m, "Hall"));
  robot.traverse(edge(f.m, "Hall_Office"));  // an hour empty away from the dock: carried back
  f.clock.run_until(kStart + minutes(62));
  ASSERT_EQ(f.rec.edges.size(), 3u);
  EXPECT_FALSE(f.rec.edges[2].succeeded());
  EXPECT_EQ(robot.location(), node(f.m, "Dock"));
  EXPECT_EQ(robot.rescues(), 1);
  EXPECT_TRUE(robot.charging());
  f.clock.run_until(kStart + minutes(122));
  EXPECT_NEAR(robot.battery(), 0.61, 1e-6);  // charging from 61 min
}

TEST(SimRobot, AnEmptyBatteryFailsAtOnceUntilCharged) {
  Fixture f;
  f.world.battery.initial = 0.0;
  SimRobot robot(f.clock, f.m, f.world, {.start = node(f.m, "Hall"), .dock = node(f.m, "Dock")});
  robot.set_listener(&f.rec);
  robot.traverse(edge(f.m, "Hall_Office"));
  f.clock.run_until(kStart + minutes(1));
  robot.run_action(Action{"look", {}}, minutes(1));
  f.clock.run_until(kStart + minutes(2));
  ASSERT_EQ(f.rec.edges.size(), 1u);
  EXPECT_FALSE(f.rec.edges[0].succeeded());
  EXPECT_EQ(f.rec.edges[0].duration, Duration{0});
  ASSERT_EQ(f.rec.actions.size(), 1u);
  EXPECT_EQ(f.rec.actions[0].outcome, exec::ActionOutcome::kFailed);
  EXPECT_EQ(f.rec.actions[0].message, "battery empty");
  EXPECT_EQ(robot.location(), node(f.m, "Hall"));
}

TEST(SimRobot, MisuseThrows) {
  Fixture f;
  EXPECT_THROW(f.robot.traverse(edge(f.m, "Hall_Office")), std::logic_error);  // does not leave Dock
  f.robot.traverse(edge(f.m, "Dock_Hall"));
  EXPECT_THROW(f.robot.run_action(Action{"x", {}}, minutes(1)), std::logic_error);
}

TEST(SimRobot, TheDestructorForgetsPendingEvents) {
  Fixture f;
  {
    SimRobot robot(f.clock, f.m, f.world, {.start = node(f.m, "Dock"), .dock = node(f.m, "Dock")});
    robot.set_listener(&f.rec);
    robot.traverse(edge(f.m, "Dock_Hall"));
  }
  f.clock.run_until(kStart + hours(1));
  EXPECT_TRUE(f.rec.edges.empty());
}

// A random walk on the G4S example world, twice with one seed and once with another.
std::vector<exec::EdgeAttempt> walk(std::uint64_t seed) {
  const auto& m = g4s_map();
  auto world = load_world("examples/g4s/world.yaml", m, london()).value();
  exec::SimClock clock(kStart);
  Recorder rec(clock);
  SimRobot robot(clock, m, world, {.start = node(m, "ChargingPoint"), .dock = node(m, "ChargingPoint"), .seed = seed});
  robot.set_listener(&rec);
  Rng choose(99);
  for (int i = 0; i < 300; ++i) {
    const auto out = m.out_edges(robot.location());
    robot.traverse(out[choose.uniform_int(out.size())]);
    while (robot.busy()) clock.step();
  }
  return rec.edges;
}

bool same(const std::vector<exec::EdgeAttempt>& a, const std::vector<exec::EdgeAttempt>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].edge != b[i].edge || a[i].start != b[i].start || a[i].duration != b[i].duration ||
        a[i].outcome != b[i].outcome) {
      return false;
    }
  }
  return true;
}

TEST(SimRobot, SameSeedSameLifeDifferentSeedDifferent) {
  const auto a = walk(1);
  EXPECT_EQ(a.size(), 300u);
  EXPECT_TRUE(same(a, walk(1)));
  EXPECT_FALSE(same(a, walk(2)));
}

// Any sequence of commands, cancels and waits: one callback per command, never from inside a call,
// and the robot is where its edge outcomes say.
RC_GTEST_PROP(SimRobot, KeepsTheRobotContractUnderRandomUse, ()) {
  const auto m = small_map();
  SimWorld world = exact_world(m, 0.3);
  exec::SimClock clock(kStart);
  Recorder rec(clock);
  SimRobot robot(clock, m, world, {.start = 0, .dock = 0, .seed = *rc::gen::arbitrary<std::uint64_t>()});
  robot.set_listener(&rec);
  const auto steps = *rc::gen::container<std::vector<int>>(rc::gen::inRange(0, 6));
  std::size_t commands = 0;
  map::NodeIndex expected_location = 0;
  std::size_t seen_edges = 0;
  for (int step : steps) {
    rec.inside_call = true;
    if (step <= 1 && !robot.busy()) {
      const auto out = m.out_edges(robot.location());
      robot.traverse(out[static_cast<std::size_t>(step) % out.size()]);
      ++commands;
    } else if (step == 2 && !robot.busy()) {
      robot.run_action(Action{commands % 2 == 0 ? "talk" : "look", {}}, minutes(3));
      ++commands;
    } else if (step == 3) {
      robot.cancel();
    }
    rec.inside_call = false;
    if (step >= 4) clock.run_until(clock.now() + seconds(20 * step));
    for (; seen_edges < rec.edges.size(); ++seen_edges) {
      const auto& a = rec.edges[seen_edges];
      RC_ASSERT(m.from_index(a.edge) == expected_location);
      if (a.succeeded()) expected_location = m.to_index(a.edge);
    }
    RC_ASSERT(robot.location() == expected_location);
  }
  clock.run_until(clock.now() + hours(2));
  RC_ASSERT(!robot.busy());
  RC_ASSERT(rec.edges.size() + rec.actions.size() == commands);
  RC_ASSERT(rec.calls_from_inside == 0);
  for (const auto& a : rec.edges) RC_ASSERT(a.outcome != exec::EdgeOutcome::kRobotFault);
}

}  // namespace
}  // namespace rondo::sim
