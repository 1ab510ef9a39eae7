// A deployment of several robots (`robots:`, docs/fleet.md): validation names the file, the line
// and the field of every mistake (two robots with one name, a dock or a start not on the map, a
// dock with more robots than room, an action no robot runs, a task naming a robot the deployment
// does not have), and `rondo run` drives every robot in one world, with a report per robot.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "cli_runner.h"
#include "deployment.h"
#include "g4s_copy.h"
#include "rondo/core/document.h"
#include "rondo/store/events.h"
#include "rondo/store/store.h"
#include "test_files.h"

namespace rondo {
namespace {

using test::slurp;
using ::testing::HasSubstr;

std::filesystem::path fresh_dir(const std::string& name) {
  return test::fresh_dir("rondo-fleet-deploy", name);
}

// Three robots on the G4S example: two that run everything it asks, one that only checks doors.
const std::string kRobots =
    "robots:\n"
    "  - {name: r1}\n"
    "  - {name: r2, dock: WayPoint3, start: WayPoint4}\n"
    "  - {name: checker, dock: WayPoint5, actions: [door_check], speed: 0.8}\n";

// A copy of the G4S example as a fleet: `robots` added to the deployment, then each (from, to) of
// `edits` applied to its file (the text must occur).
std::filesystem::path fleet_example(const std::filesystem::path& dir, const std::string& robots,
                                    const std::vector<std::tuple<std::string, std::string, std::string>>& edits = {}) {
  const auto deployment = test::copy_g4s(dir);
  std::ofstream(deployment, std::ios::app) << robots;
  for (const auto& [file, from, to] : edits) test::replace_in(dir / file, from, to);
  return deployment;
}

using test::line_of;

TEST(FleetDeployment, RobotsAreReadWithTheirDocksStartsActionsAndSpeeds) {
  const auto dir = fresh_dir("read");
  const auto d = app::load_deployment(fleet_example(dir, kRobots));
  ASSERT_TRUE(d.ok()) << d.error().message;
  ASSERT_EQ(d->robots.size(), 3u);
  EXPECT_EQ(d->robots[0].name, "r1");
  EXPECT_EQ(d->robots[0].dock, "");  // the deployment's
  EXPECT_EQ(d->robots[1].dock, "WayPoint3");
  EXPECT_EQ(d->robots[1].start, "WayPoint4");
  ASSERT_TRUE(d->robots[2].actions.has_value());
  EXPECT_EQ(*d->robots[2].actions, std::vector<std::string>{"door_check"});
  EXPECT_DOUBLE_EQ(d->robots[2].speed, 0.8);
  EXPECT_FALSE(d->has_vehicle());
  EXPECT_EQ(d->allocator, app::AllocatorKind::kFleet);  // the default
}

TEST(FleetDeployment, TheAllocatorIsChosenByName) {
  const auto dir = fresh_dir("allocator");
  const auto d = app::load_deployment(fleet_example(dir, kRobots + "allocator: greedy\n"));
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->allocator, app::AllocatorKind::kGreedy);
}

TEST(FleetDeployment, OneRobotIsAFleetOfOneNamedRobot) {
  const auto d = app::load_deployment("examples/g4s/deployment.yaml");
  ASSERT_TRUE(d.ok()) << d.error().message;
  ASSERT_EQ(d->robots.size(), 1u);
  EXPECT_EQ(d->robots[0].name, "robot");
  EXPECT_FALSE(d->robots[0].vda5050.has_value());
}

TEST(FleetDeployment, ADockWithRoomForTwoTakesTwoRobots) {
  const auto dir = fresh_dir("room");
  const auto d = app::load_deployment(
      fleet_example(dir, "docks: [{node: ChargingPoint, capacity: 2}]\nrobots:\n  - {name: a}\n  - {name: b}\n"));
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->dock_capacity("ChargingPoint"), 2);
  EXPECT_EQ(d->dock_capacity("WayPoint3"), 1);
}

struct Mistake {
  const char* name;
  std::string robots;  // the deployment's robots (and docks)
  std::vector<std::tuple<std::string, std::string, std::string>> edits;
  const char* file;  // named in the error, with the line where `at` stands
  const char* at;
  const char* says;
};

void PrintTo(const Mistake& m, std::ostream* os) {
  *os << m.name;
}

class FleetMistake : public ::testing::TestWithParam<Mistake> {};

TEST_P(FleetMistake, IsExitCode2NamingTheFileTheLineAndTheField) {
  const Mistake& m = GetParam();
  const auto dir = fresh_dir(m.name);
  const auto deployment = fleet_example(dir, m.robots, m.edits);
  const auto r = test::run_cli({"run", deployment.string(), "--days", "1", "--out", (dir / "run").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr(std::string(m.file) + ":" + std::to_string(line_of(slurp(dir / m.file), m.at))));
  EXPECT_THAT(r.err, HasSubstr(m.says));
  EXPECT_FALSE(std::filesystem::exists(dir / "run"));
}

INSTANTIATE_TEST_SUITE_P(
    RunCommand, FleetMistake,
    ::testing::Values(Mistake{"two-names",
                              "robots:\n  - {name: r1, dock: WayPoint3}\n  - {name: r1, dock: WayPoint5}\n",
                              {},
                              "deployment.yaml",
                              "{name: r1, dock: WayPoint5}",
                              "two robots are named 'r1'"},
                      Mistake{"dock-off-map",
                              "robots:\n  - {name: r1}\n  - {name: r2, dock: Basement}\n",
                              {},
                              "deployment.yaml",
                              "{name: r2, dock: Basement}",
                              "node 'Basement' is not on the map"},
                      Mistake{"start-off-map",
                              "robots:\n  - {name: r1, start: Roof}\n",
                              {},
                              "deployment.yaml",
                              "{name: r1, start: Roof}",
                              "node 'Roof' is not on the map"},
                      Mistake{"listed-dock-off-map",
                              "docks: [{node: Cellar, capacity: 2}]\nrobots:\n  - {name: r1}\n",
                              {},
                              "deployment.yaml",
                              "{node: Cellar",
                              "node 'Cellar' is not on the map"},
                      Mistake{"dock-without-room",
                              "robots:\n  - {name: r1}\n  - {name: r2}\n",
                              {},
                              "deployment.yaml",
                              "{name: r2}",
                              "dock 'ChargingPoint' has room for 1 robot, and 2 robots have it as their dock"},
                      Mistake{"two-starts-on-one-node",
                              "robots:\n  - {name: r1, start: WayPoint4}\n  - {name: r2, dock: WayPoint3, start: "
                              "WayPoint4}\n",
                              {},
                              "deployment.yaml",
                              "{name: r2, dock: WayPoint3",
                              "robots[1].start: node 'WayPoint4' holds 1 robot at once, and 2 simulated robots start "
                              "there ('r1', 'r2')"},
                      Mistake{"action-nobody-runs",
                              "robots:\n  - {name: r1, actions: [door_check, extinguisher_check]}\n",
                              {},
                              "routines.yaml",
                              "actions: [map_3d]",
                              "no robot of the deployment runs 'map_3d'"},
                      Mistake{"unknown-robot",
                              kRobots,
                              {{"routines.yaml", "start_node: WayPoint2,", "start_node: WayPoint2, robot: r9,"}},
                              "routines.yaml",
                              "robot: r9",
                              "'r9' is not a robot of the deployment (it has: r1, r2, checker)"},
                      Mistake{"robot-and-robots",
                              "robot: {kind: sim}\n" + kRobots,
                              {},
                              "deployment.yaml",
                              "- {name: r1}",
                              "robot and robots are both given"},
                      Mistake{"no-robots", "robots: []\n", {}, "deployment.yaml", "robots:", "lists no robot"},
                      Mistake{"unknown-allocator",
                              kRobots + "allocator: best\n",
                              {},
                              "deployment.yaml",
                              "allocator: best",
                              "allocator: 'best' is not an allocator (fleet or greedy)"}),
    [](const ::testing::TestParamInfo<Mistake>& param) {
      std::string n = param.param.name;
      std::replace(n.begin(), n.end(), '-', '_');
      return n;
    });

// Two days of the G4S example with three robots in one world: every robot works, each task ran on
// one robot at a time (its events name one robot between its re-allocations: a task moves only when
// the fleet takes it back, queued, from a robot that preempted it or cannot work), and the report
// has a section per robot, whose tasks and distances add up to the fleet's.
TEST(FleetRun, EveryRobotWorksAndEachTaskRunsOnOneRobot) {
  const auto dir = fresh_dir("run");
  const auto deployment = fleet_example(dir, kRobots);
  const auto out = dir / "run";
  const auto r = test::run_cli({"run", deployment.string(), "--days", "2", "--out", out.string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json report = Json::parse(r.out);
  ASSERT_TRUE(report.contains("robots"));
  ASSERT_EQ(report["robots"].size(), 3u);
  int allocated = 0;
  double distance = 0;
  for (const Json& robot : report["robots"]) {
    EXPECT_GT(robot["tasks"]["succeeded"].get<int>(), 0) << robot.dump();
    EXPECT_GT(robot["distance_m"].get<double>(), 0) << robot.dump();
    allocated += robot["tasks"]["allocated"].get<int>();
    distance += robot["distance_m"].get<double>();
  }
  EXPECT_EQ(allocated, report["tasks"]["added"].get<int>());
  EXPECT_NEAR(distance, report["navigation"]["distance_m"].get<double>(), 0.5);
  // Three robots in one building: their meetings (docs/simulation.md, "Traffic").
  ASSERT_TRUE(report.contains("traffic"));
  const Json& traffic = report["traffic"];
  EXPECT_EQ(traffic["hold_timeout_s"], 60.0);
  const Json& holds = traffic["hold_ups"];
  EXPECT_EQ(holds["count"].get<int>(),
            holds["passed"].get<int>() + holds["timed_out"].get<int>() + holds["stopped"].get<int>());
  EXPECT_LE(holds["longest_s"].get<double>(), 60.0);
  EXPECT_LE(holds["first"].size(), 5u);
  EXPECT_EQ(traffic["collisions"]["count"].get<int>(),
            traffic["collisions"]["at_nodes"].get<int>() + traffic["collisions"]["on_narrow_edges"].get<int>());
  // They reserve their way (docs/traffic.md): nobody is held up in the simulator, nobody collides;
  // their waits are the executive's, each ended one way.
  EXPECT_EQ(holds["count"].get<int>(), 0) << traffic.dump();
  EXPECT_EQ(traffic["collisions"]["count"].get<int>(), 0) << traffic.dump();
  ASSERT_TRUE(traffic.contains("reservations"));
  const Json& waits = traffic["reservations"]["waits"];
  EXPECT_GE(waits["count"].get<int>(),
            waits["passed"].get<int>() + waits["made_way"].get<int>() + waits["stopped"].get<int>());
  EXPECT_EQ(traffic["reservations"]["lookahead"].get<int>(), 2);
  for (const char* name : {"r1", "r2", "checker"})
    for (const char* day : {"2026-11-23", "2026-11-24"})
      EXPECT_TRUE(std::filesystem::exists(out / "days" / (std::string(day) + "-" + name + ".svg"))) << name << day;

  // The event log (in order): between two re-allocations, every event of a task names one robot.
  auto db = store::Store::open(out / "rondo.sqlite");
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto events = store::read_events(*db);
  ASSERT_TRUE(events.ok()) << events.error().message;
  std::map<std::string, std::set<std::string>> robots_of;  // task -> robots its events name since its last move
  int with_robot = 0;
  for (const store::Event& e : *events) {
    if (e.task_id.empty() || e.robot.empty()) continue;
    if (e.event == "re-allocated") robots_of[e.task_id].clear();
    robots_of[e.task_id].insert(e.robot);
    EXPECT_EQ(robots_of[e.task_id].size(), 1u) << e.task_id << " at event " << e.seq << ": " << e.event;
    ++with_robot;
  }
  EXPECT_GT(with_robot, 0);
}

// A robot alone has no traffic: its report has no `traffic` section (and is as it was).
TEST(FleetRun, ALoneRobotsReportHasNoTraffic) {
  const auto dir = fresh_dir("alone");
  const auto r =
      test::run_cli({"run", test::copy_g4s(dir).string(), "--days", "1", "--out", (dir / "run").string(), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(Json::parse(r.out).contains("traffic"));
}

}  // namespace
}  // namespace rondo
