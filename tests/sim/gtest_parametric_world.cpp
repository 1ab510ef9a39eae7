#include "rondo/sim/parametric_world.h"

#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim_test_util.h"

namespace rondo::sim {
namespace {

using namespace rondo::sim::testing;

// The kitchen is crowded at lunch on weekdays; its door is closed out of office hours.
ParametricSpec office_spec(const map::TopoMap& m) {
  ParametricSpec spec;
  spec.failure_probability = 0.02;
  spec.effects.push_back({.name = "lunch",
                          .edges = {edge(m, "Hall_Office"), edge(m, "Office_Hall")},
                          .when = {{.days = weekdays(), .from = hours(12), .to = hours(13) + minutes(30)}},
                          .failure_probability = 0.3,
                          .duration_factor = 2.0});
  spec.effects.push_back({.name = "door closed out of hours",
                          .edges = {edge(m, "Hall_Kitchen"), edge(m, "Kitchen_Hall")},
                          .unless = {{.days = weekdays(), .from = hours(8), .to = hours(18) + minutes(30)}},
                          .closed = true});
  return spec;
}

struct Rate {
  double failures = 0;
  double mean_success_s = 0;
};

// Attempts on `e` at `time_of_day` on each of the next `days` weekdays, one fresh world a day so
// that nothing but the time of day differs between two calls.
Rate rate_at(const map::TopoMap& m, const ParametricSpec& spec, map::EdgeIndex e, Duration time_of_day, int days,
             std::uint64_t seed) {
  Rng rng(seed);
  ParametricWorld world(m, london(), spec);
  int fails = 0, ok = 0;
  double sum = 0;
  const Time monday = local("2026-11-23T00:00");
  for (int d = 0, used = 0; used < days; ++d) {
    const Time t = monday + std::chrono::days(d) + time_of_day;
    const auto wd = london().day_of_week(t);
    if (wd == std::chrono::Saturday || wd == std::chrono::Sunday) continue;
    ++used;
    for (int k = 0; k < 20; ++k) {
      const EdgeSample s = world.sample_edge(e, t + seconds(k), rng);
      if (s.success) {
        ++ok;
        sum += to_seconds(s.duration);
      } else {
        ++fails;
      }
    }
  }
  return {static_cast<double>(fails) / (fails + ok), ok > 0 ? sum / ok : 0.0};
}

TEST(ParametricWorld, SameSeedSameSamplesDifferentSeedDifferent) {
  const auto m = small_map();
  ParametricSpec spec = office_spec(m);
  spec.bursts = {.mean_normal = hours(2), .mean_blocked = minutes(20)};
  auto run = [&](std::uint64_t seed) {
    ParametricWorld world(m, london(), spec);
    Rng rng(seed);
    std::vector<std::pair<bool, Duration>> out;
    Time t = local("2026-11-23T07:00");
    for (int i = 0; i < 300; ++i, t += minutes(3)) {
      const EdgeSample s = world.sample_edge(static_cast<map::EdgeIndex>(i) % m.edge_count(), t, rng);
      out.emplace_back(s.success, s.duration);
    }
    return out;
  };
  EXPECT_EQ(run(5), run(5));
  EXPECT_NE(run(5), run(6));
}

TEST(ParametricWorld, LunchCrowdFailsMoreAndIsSlower) {
  const auto m = small_map();
  const auto spec = office_spec(m);
  const auto e = edge(m, "Hall_Office");
  const Rate lunch = rate_at(m, spec, e, hours(12) + minutes(40), 100, 1);
  const Rate morning = rate_at(m, spec, e, hours(10) + minutes(40), 100, 1);
  // 1 - 0.98 · 0.7 = 0.314 at lunch, 0.02 otherwise (2000 attempts each).
  EXPECT_NEAR(lunch.failures, 0.314, 0.04);
  EXPECT_NEAR(morning.failures, 0.02, 0.012);
  EXPECT_NEAR(lunch.mean_success_s / morning.mean_success_s, 2.0, 0.25);
  // Outside the crowd the edge keeps its nominal time: 10 m at 0.45 m/s, lognormal mean ≈ 1.02.
  EXPECT_NEAR(morning.mean_success_s, 22.2, 3.0);
}

TEST(ParametricWorld, DoorsAreClosedOutOfHoursAndAtWeekends) {
  const auto m = small_map();
  ParametricWorld world(m, london(), office_spec(m));
  Rng rng(2);
  const auto door = edge(m, "Hall_Kitchen");
  int open_successes = 0;
  for (int i = 0; i < 200; ++i) {
    const Duration jitter = minutes(i % 60);
    EXPECT_FALSE(world.sample_edge(door, local("2026-11-23T19:00") + jitter, rng).success);  // Monday evening
    EXPECT_FALSE(world.sample_edge(door, local("2026-11-24T07:00") + jitter, rng).success);  // Tuesday early
    EXPECT_FALSE(world.sample_edge(door, local("2026-11-28T11:00") + jitter, rng).success);  // Saturday
    if (world.sample_edge(door, local("2026-11-25T11:00") + jitter, rng).success) ++open_successes;
  }
  EXPECT_GT(open_successes, 180);  // Wednesday morning: only the base failure rate
}

// With bursts, a failure is followed by another far more often than the overall rate says.
TEST(ParametricWorld, FailuresComeInBursts) {
  const auto m = small_map();
  ParametricSpec spec;
  spec.failure_probability = 0.02;
  spec.bursts = {.mean_normal = hours(3), .mean_blocked = minutes(20), .failure_probability = 0.8};
  ParametricWorld world(m, london(), spec);
  Rng rng(9);
  const auto e = edge(m, "Hall_Office");
  int n = 0, fails = 0, after_fail = 0, fail_after_fail = 0;
  bool previous_failed = false;
  for (Time t = local("2026-11-23T00:00"); t < local("2026-12-21T00:00"); t += minutes(2)) {
    const bool failed = !world.sample_edge(e, t, rng).success;
    ++n;
    fails += failed ? 1 : 0;
    if (previous_failed) {
      ++after_fail;
      fail_after_fail += failed ? 1 : 0;
    }
    previous_failed = failed;
  }
  const double rate = static_cast<double>(fails) / n;
  const double conditional = static_cast<double>(fail_after_fail) / after_fail;
  // Stationary blocked share 20/200 = 0.1: overall ≈ 0.02 + 0.98 · 0.1 · 0.8 ≈ 0.098.
  EXPECT_NEAR(rate, 0.098, 0.03);
  EXPECT_GT(conditional, 4 * rate);
}

// The burst state's exact transition law against a slow step-by-step simulation of the same chain.
TEST(ParametricWorld, BurstTransitionsMatchAStepSimulation) {
  const auto m = small_map();
  ParametricSpec spec;
  spec.bursts = {.mean_normal = minutes(40), .mean_blocked = minutes(20)};
  const auto e = edge(m, "Hall_Office");
  const Time t0 = local("2026-11-23T09:00");
  const Duration gap = minutes(15);
  Rng rng(21);
  int blocked_first = 0, still_blocked = 0;
  for (int i = 0; i < 20000; ++i) {
    ParametricWorld world(m, london(), spec);
    if (!world.conditions(e, t0, rng).blocked) continue;
    ++blocked_first;
    still_blocked += world.conditions(e, t0 + gap, rng).blocked ? 1 : 0;
  }
  // Reference: 1 s steps, leaving the blocked state with probability 1/1200 and entering it with
  // 1/2400 per step.
  Rng ref_rng(22);
  int ref_still = 0;
  const int runs = 4000;
  for (int i = 0; i < runs; ++i) {
    bool blocked = true;
    for (int s = 0; s < 900; ++s) blocked = blocked ? !ref_rng.bernoulli(1.0 / 1200) : ref_rng.bernoulli(1.0 / 2400);
    ref_still += blocked ? 1 : 0;
  }
  ASSERT_GT(blocked_first, 5000);  // stationary share 1/3
  EXPECT_NEAR(static_cast<double>(still_blocked) / blocked_first, static_cast<double>(ref_still) / runs, 0.04);
}

RC_GTEST_PROP(ParametricWorld, ClosedEdgesAlwaysFailAndDurationsAreNonNegative,
              (std::uint64_t seed, std::uint32_t minutes_into_week)) {
  const auto m = small_map();
  ParametricSpec spec = office_spec(m);
  spec.noise.sigma = 1.0;
  spec.bursts = {.mean_normal = hours(1), .mean_blocked = hours(1)};
  ParametricWorld world(m, london(), spec);
  Rng rng(seed);
  const Time t = local("2026-11-23T00:00") + minutes(minutes_into_week % (7 * 24 * 60));
  const auto tod = london().time_of_day(t);
  const auto wd = london().day_of_week(t);
  const bool office = wd != std::chrono::Saturday && wd != std::chrono::Sunday && tod >= hours(8) &&
                      tod < hours(18) + minutes(30);
  for (map::EdgeIndex e = 0; e < m.edge_count(); ++e) {
    const EdgeSample s = world.sample_edge(e, t, rng);
    RC_ASSERT(s.duration >= Duration{0});
    if (!office && m.edge(e).door) RC_ASSERT(!s.success);
  }
}

// The kitchen door "kd" is shut for spells of 30 minutes on average, open 90 minutes between
// them: a quarter of the time.
ParametricSpec spells_spec(const map::TopoMap& m) {
  ParametricSpec spec;
  spec.failure_probability = 0;
  spec.effects.push_back({.name = "kitchen shut now and then",
                          .edges = {edge(m, "Hall_Kitchen"), edge(m, "Kitchen_Hall")},
                          .spells = ShutSpells{.mean_open = minutes(90), .mean_shut = minutes(30)}});
  return spec;
}

// A shut spell holds for both directions of the door, every attempt in it fails, and the door
// sensor's view (closed_at) is the same spell.
TEST(ParametricWorld, AShutSpellLastsAndHoldsForBothDirectionsAndTheSensor) {
  const map::TopoMap m = small_map();
  ParametricWorld world(m, london(), spells_spec(m));
  world.set_seed(5);
  Rng rng(1);
  const map::EdgeIndex in = edge(m, "Hall_Kitchen"), out = edge(m, "Kitchen_Hall");
  int shut_minutes = 0, runs = 0;
  bool was_shut = false;
  const Time monday = local("2026-11-23T00:00");
  for (Time t = monday; t < monday + hours(24 * 7); t += minutes(1)) {
    const bool shut = *world.closed_at(in, t);
    EXPECT_EQ(*world.closed_at(out, t), shut);
    if (shut) {
      EXPECT_FALSE(world.sample_edge(in, t, rng).success);
      EXPECT_FALSE(world.sample_edge(out, t, rng).success);
    } else {
      EXPECT_TRUE(world.sample_edge(in, t, rng).success);
    }
    shut_minutes += shut ? 1 : 0;
    runs += (shut && !was_shut) ? 1 : 0;
    was_shut = shut;
  }
  // A week: about a quarter shut, in spells of about half an hour (not minute by minute).
  const double share = shut_minutes / (7.0 * 24 * 60);
  EXPECT_NEAR(share, 0.25, 0.08);
  ASSERT_GT(runs, 0);
  EXPECT_NEAR(static_cast<double>(shut_minutes) / runs, 30.0, 12.0);
  EXPECT_FALSE(*world.closed_at(edge(m, "Dock_Hall"), monday));  // no door, no effect
}

// The spells are a function of the seed and the time: the order of the looks does not matter, a
// fresh world with the same seed sees the same, another seed sees other spells.
TEST(ParametricWorld, ShutSpellsDependOnTheSeedAndTheTimeOnly) {
  const map::TopoMap m = small_map();
  const map::EdgeIndex door = edge(m, "Hall_Kitchen");
  const Time monday = local("2026-11-23T00:00");
  std::vector<Time> times;
  for (int i = 0; i < 2000; ++i) times.push_back(monday + minutes(7 * i));
  const auto looks = [&](std::uint64_t seed, bool backwards) {
    ParametricWorld world(m, london(), spells_spec(m));
    world.set_seed(seed);
    std::vector<bool> shut(times.size());
    for (std::size_t k = 0; k < times.size(); ++k) {
      const std::size_t i = backwards ? times.size() - 1 - k : k;
      shut[i] = *world.closed_at(door, times[i]);
    }
    return shut;
  };
  EXPECT_EQ(looks(5, false), looks(5, true));
  EXPECT_NE(looks(5, false), looks(6, false));
}

}  // namespace
}  // namespace rondo::sim
