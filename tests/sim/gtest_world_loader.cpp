#include <gtest/gtest.h>

#include <string>

#include "rondo/sim/parametric_world.h"
#include "rondo/sim/replay_world.h"
#include "rondo/sim/sim_world.h"
#include "sim_test_util.h"

namespace rondo::sim {
namespace {

using namespace rondo::sim::testing;

Result<SimWorld> parse(const std::string& text, const map::TopoMap& m) {
  auto doc = Document::parse(text, DocumentFormat::kYaml, "world.yaml");
  if (!doc) return doc.error();
  return decode_world(*doc, ".", m, london());
}

TEST(LoadWorld, TheG4sExampleHasItsRhythms) {
  const auto& m = g4s_map();
  auto world = load_world("examples/g4s/world.yaml", m, london());
  ASSERT_TRUE(world.ok()) << world.error().message;
  auto* parametric = dynamic_cast<ParametricWorld*>(world->edges.get());
  ASSERT_NE(parametric, nullptr);
  const auto& effects = parametric->spec().effects;
  ASSERT_EQ(effects.size(), 4u);
  EXPECT_EQ(effects[2].edges.size(), 18u);  // every doorPassing edge of g4s_y2
  EXPECT_TRUE(effects[2].closed);
  EXPECT_EQ(effects[3].edges.size(), 2u);
  EXPECT_EQ(parametric->spec().bursts.mean_blocked, minutes(15));
  EXPECT_GT(world->actions.profile("talk").non_interruptible, Duration{0});
  for (const char* name : {"door_check", "extinguisher_check", "map_3d", "object_search", "talk", "deliver"}) {
    EXPECT_NE(world->actions.profile(name), world->actions.profile("not-an-action")) << name;
  }
  Rng rng(1);
  const auto door = edge(m, "WayPoint1_WayPoint2");
  EXPECT_FALSE(world->edges->sample_edge(door, local("2026-11-28T12:00"), rng).success);  // Saturday
}

TEST(LoadWorld, TheWithamExampleReplaysTheLogs) {
  const auto& m = witham_map();
  auto world = load_world("examples/witham/world.yaml", m, london());
  ASSERT_TRUE(world.ok()) << world.error().message;
  auto* replay = dynamic_cast<ReplayWorld*>(world->edges.get());
  ASSERT_NE(replay, nullptr);
  EXPECT_EQ(replay->unmatched_records(), 0u);
  EXPECT_EQ(replay->attempts(edge(m, "LabDoor1_LabDoor2")).size(), 4966u);
}

struct BadWorld {
  const char* text;
  const char* message;  // a part of the expected message
};

class LoadWorldErrors : public ::testing::TestWithParam<BadWorld> {};

TEST_P(LoadWorldErrors, NameTheFileLineAndField) {
  auto world = parse(GetParam().text, small_map());
  ASSERT_FALSE(world.ok());
  EXPECT_NE(world.error().message.find(GetParam().message), std::string::npos) << world.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Table, LoadWorldErrors,
    ::testing::Values(
        BadWorld{"kind: weather\n", "world.yaml:1: kind: unknown kind 'weather'"},
        BadWorld{"speed: 1\n", "kind"},
        BadWorld{"kind: parametric\nsped: 1\n", "sped"},
        BadWorld{"kind: parametric\nfailure_probability: 1.5\n", "world.yaml:2: failure_probability: must be from 0 to 1"},
        BadWorld{"kind: parametric\neffects:\n  - nodes: [Hall]\n  - nodes: [Attic]\n", "world.yaml:4: effects[1].nodes[0]: map 'small' has no node 'Attic'"},
        BadWorld{"kind: parametric\neffects:\n  - actions: [doorPasing]\n", "effects[0].actions[0]: map 'small' has no edge with action 'doorPasing'"},
        BadWorld{"kind: parametric\neffects:\n  - closed: true\n", "world.yaml:3: effects[0]: an effect needs edges"},
        BadWorld{"kind: parametric\neffects:\n  - all: true\n    when: {days: [funday]}\n", "world.yaml:4: effects[0].when.days[0]: unknown day 'funday'"},
        BadWorld{"kind: parametric\neffects:\n  - all: true\n    when: {from: \"25:00\"}\n", "effects[0].when.from: a time of day"},
        BadWorld{"kind: parametric\nbursts: {mean_blocked: soon}\n", "world.yaml:2: bursts.mean_blocked"},
        BadWorld{"kind: parametric\neffects:\n  - doors: [kd]\n    spells: {mean_open: 1h}\n", "world.yaml:4: effects[0].spells: mean_open and mean_shut"},
        BadWorld{"kind: parametric\neffects:\n  - doors: [kd]\n    spells: {mean_open: 1h, mean_shut: 10m, often: 2}\n", "often"},
        BadWorld{"kind: parametric\nactions:\n  talk: {non_interruptible: -1}\n", "world.yaml:3: actions.talk.non_interruptible"},
        BadWorld{"kind: parametric\nbattery: {charging_per_hour: -2}\n", "world.yaml:2: battery.charging_per_hour: must be from 0"},
        BadWorld{"kind: parametric\nbattery:\n  per_metre: 2\n", "world.yaml:3: battery.per_metre: must be from 0 to 1"},
        BadWorld{"kind: parametric\nbattery: {per_meter: 0.001}\n", "per_meter"},
        BadWorld{"kind: parametric\nbattery: {rescue_after: 0s}\n", "world.yaml:2: battery.rescue_after: must be positive"},
        BadWorld{"kind: parametric\nconfirmation: {places: {Attic: 2m}}\n", "world.yaml:2: confirmation.places.Attic: map 'small' has no node 'Attic'"},
        BadWorld{"kind: parametric\nconfirmation: {default: 0s}\n", "world.yaml:2: confirmation.default: must be positive"},
        BadWorld{"kind: parametric\nconfirmation: {by: 2m}\n", "by"},
        BadWorld{"kind: replay\n", "logs"},
        BadWorld{"kind: replay\nlogs: no/such/folder\n", "world.yaml:2: logs: './no/such/folder' is not a folder"},
        BadWorld{"kind: replay\nlogs: .\nlog_timezone: Mars/Olympus\n", "world.yaml:3: log_timezone"}));

TEST(LoadWorld, TheBatteryDrainsByTheMetreOnlyWhenTheFileSaysSo) {
  auto plain = parse("kind: parametric\nbattery: {moving_per_hour: 0.3}\n", small_map());
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_EQ(plain->battery.moving_per_hour, 0.3);
  EXPECT_EQ(plain->battery.per_metre, 0.0);  // old files keep their battery
  auto metered = parse("kind: parametric\nbattery: {per_metre: 0.0002, charging_per_hour: 0.4}\n", small_map());
  ASSERT_TRUE(metered.ok()) << metered.error().message;
  EXPECT_EQ(metered->battery.per_metre, 0.0002);
  EXPECT_EQ(metered->battery.charging_per_hour, 0.4);
}

TEST(LoadWorld, TheHoldTimeoutOfTheTrafficIsAMinuteUnlessTheFileSays) {
  auto plain = parse("kind: parametric\n", small_map());
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_EQ(plain->traffic.hold_timeout, seconds(60));
  auto set = parse("kind: parametric\ntraffic: {hold_timeout: 90s}\n", small_map());
  ASSERT_TRUE(set.ok()) << set.error().message;
  EXPECT_EQ(set->traffic.hold_timeout, seconds(90));
  auto zero = parse("kind: parametric\ntraffic: {hold_timeout: 0s}\n", small_map());
  ASSERT_FALSE(zero.ok());
  EXPECT_NE(zero.error().message.find("world.yaml:2: traffic.hold_timeout: must be a duration above 0"),
            std::string::npos)
      << zero.error().message;
  auto unknown = parse("kind: parametric\ntraffic: {patience: 1m}\n", small_map());
  ASSERT_FALSE(unknown.ok());
  EXPECT_NE(unknown.error().message.find("patience"), std::string::npos) << unknown.error().message;
}

TEST(LoadWorld, AMissingFileIsNotFound) {
  auto world = load_world("examples/g4s/no-such-world.yaml", small_map(), london());
  ASSERT_FALSE(world.ok());
  EXPECT_EQ(world.error().code, ErrorCode::kNotFound);
}

}  // namespace
}  // namespace rondo::sim
