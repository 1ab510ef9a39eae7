#include "rondo/sim/replay_world.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <set>

#include "rondo/core/traversal.h"
#include "sim_test_util.h"

namespace rondo::sim {
namespace {

using namespace rondo::sim::testing;

constexpr Duration kWeek = std::chrono::days(7);

const std::vector<Traversal>& witham_log() {
  static const std::vector<Traversal> log = read_witham_logs("../shared/data/witham_wharf").value();
  return log;
}

Duration circular_distance(Duration a, Duration b) {
  const Duration d = a > b ? a - b : b - a;
  return std::min(d, kWeek - d);
}

// Reference for near(): every attempt of the edge, filtered one by one.
std::vector<Time> brute_force_near(const ReplayWorld& w, map::EdgeIndex e, Duration tow, Duration half) {
  std::vector<Time> out;
  for (const auto& a : w.attempts(e)) {
    if (half * 2 >= kWeek || circular_distance(a.time_of_week, tow) <= half) out.push_back(a.start);
  }
  std::sort(out.begin(), out.end());
  return out;
}

RC_GTEST_PROP(ReplayWorld, NearFindsExactlyTheAttemptsInTheWindow, ()) {
  const auto m = small_map();
  const auto offsets = *rc::gen::container<std::vector<std::uint32_t>>(rc::gen::inRange<std::uint32_t>(0, 4 * 7 * 24 * 60));
  std::vector<Traversal> log;
  const Time base = from_unix_seconds(1'404'000'000);
  for (std::uint32_t minute : offsets) {
    log.push_back({.edge_id = "Hall_Office", .from = "Hall", .to = "Office", .start = base + minutes(minute),
                   .duration = seconds(20), .success = true});
  }
  ReplayWorld world(m, log, TimeZone::utc(), ReplayOptions{});
  const auto e = edge(m, "Hall_Office");
  const Duration tow = minutes(*rc::gen::inRange<std::int64_t>(0, 7 * 24 * 60));
  const Duration half = minutes(*rc::gen::inRange<std::int64_t>(0, 5 * 24 * 60));
  std::vector<Time> fast;
  for (const LoggedAttempt* a : world.near(e, tow, half)) fast.push_back(a->start);
  std::sort(fast.begin(), fast.end());
  RC_ASSERT(fast == brute_force_near(world, e, tow, half));
}

TEST(ReplayWorld, DrawsComeFromTheSameTimeOfWeek) {
  const auto& m = witham_map();
  const TimeZone zone = london();
  ReplayWorld world(m, witham_log(), zone, ReplayOptions{.log_zone = london()});
  EXPECT_EQ(world.unmatched_records(), 0u);
  Rng rng(4);
  int checked = 0;
  for (Time t = local("2026-11-23T08:00"); t < local("2026-11-30T08:00"); t += minutes(37)) {
    for (map::EdgeIndex e = 0; e < m.edge_count(); e += 7) {
      const LoggedAttempt* a = world.draw(e, t, rng);
      ASSERT_NE(a, nullptr) << m.edge(e).id;  // every Witham edge has a log
      if (world.near(e, zone.time_of_week(t), minutes(30)).empty()) continue;
      EXPECT_LE(circular_distance(a->time_of_week, zone.time_of_week(t)), minutes(30)) << m.edge(e).id;
      ++checked;
    }
  }
  EXPECT_GT(checked, 500);
}

TEST(ReplayWorld, OneDayPrefersOneSourceWeek) {
  const auto& m = witham_map();
  ReplayWorld world(m, witham_log(), london(), ReplayOptions{.log_zone = london()});
  Rng rng(8);
  const Time day = local("2026-11-24T09:00");
  const std::int64_t week = world.week_for_day(day, rng);
  int same = 0, possible = 0;
  for (Time t = day; t < day + hours(8); t += minutes(5)) {
    const auto e = edge(m, "LabDoor1_LabDoor2");
    const auto pool = world.near(e, london().time_of_week(t), minutes(30));
    const bool available = std::any_of(pool.begin(), pool.end(), [&](auto* a) { return a->week == week; });
    const LoggedAttempt* a = world.draw(e, t, rng);
    if (available) {
      ++possible;
      same += a->week == week ? 1 : 0;
    }
  }
  EXPECT_GT(possible, 10);
  EXPECT_EQ(same, possible);
  EXPECT_GT(world.weeks().size(), 8u);  // 8 July - 22 September 2014
}

TEST(ReplayWorld, EdgesWithoutLogsUseThePrior) {
  const auto m = small_map();
  std::vector<Traversal> log = {{.edge_id = "Hall_Office", .from = "Hall", .to = "Office",
                                 .start = local("2026-11-23T10:00"), .duration = seconds(99), .success = false},
                                {.edge_id = "Nowhere_Else", .from = "Nowhere", .to = "Else",
                                 .start = local("2026-11-23T10:00"), .duration = seconds(5), .success = true}};
  ReplayWorld world(m, log, london(), ReplayOptions{.log_zone = london()});
  EXPECT_EQ(world.unmatched_records(), 1u);
  Rng rng(1);
  // The logged edge replays its one attempt at any time (the window widens to find it).
  const EdgeSample logged = world.sample_edge(edge(m, "Hall_Office"), local("2026-11-26T03:00"), rng);
  EXPECT_FALSE(logged.success);
  EXPECT_EQ(logged.duration, seconds(99));
  // The others come from the prior: about the nominal 10 m at 0.45 m/s.
  const EdgeSample prior = world.sample_edge(edge(m, "Office_Hall"), local("2026-11-26T03:00"), rng);
  EXPECT_EQ(world.draw(edge(m, "Office_Hall"), local("2026-11-26T03:00"), rng), nullptr);
  EXPECT_GT(prior.duration, seconds(5));
  EXPECT_LT(prior.duration, seconds(400));
}

TEST(ReplayWorld, SameSeedSameSamples) {
  const auto& m = witham_map();
  auto run = [&](std::uint64_t seed) {
    ReplayWorld world(m, witham_log(), london(), ReplayOptions{.log_zone = london()});
    Rng rng(seed);
    std::vector<std::pair<bool, Duration>> out;
    Time t = local("2026-11-23T08:00");
    for (int i = 0; i < 500; ++i, t += minutes(11)) {
      const EdgeSample s = world.sample_edge(static_cast<map::EdgeIndex>(i) % m.edge_count(), t, rng);
      out.emplace_back(s.success, s.duration);
    }
    return out;
  };
  EXPECT_EQ(run(3), run(3));
  EXPECT_NE(run(3), run(4));
}

}  // namespace
}  // namespace rondo::sim
