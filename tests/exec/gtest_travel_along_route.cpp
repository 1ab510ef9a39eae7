// Travel times along the route (TravelCache's route_threshold): where the robot reaches an edge in
// a later slot than it leaves in and the edge is slower, closed or open only then, the cache gives
// the time-dependent arrival when it differs from the departure slot's by more than the threshold;
// without a threshold, exactly the departure slot's. FIFO and the lower bound hold, and the default
// scheduler and brute force agree on problems over this travel.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "plan/random_map.h"
#include "plan/small_maps.h"
#include "rondo/exec/map_travel.h"
#include "rondo/plan/edge_model_view.h"
#include "rondo/plan/travel_planner.h"
#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"
#include "rondo/schedule/stop_condition.h"
#include "scenario.h"
#include "schedule/brute_force.h"

namespace rondo::exec {
namespace {

const Time kDepart = from_unix_seconds(1'795'392'000) + hours(8);  // a Monday, 08:00Z: a slot start
constexpr map::NodeIndex kA = 0, kC = 2;

// A>B takes 20 minutes, so a robot leaving A at a slot start reaches B>C in the next slot;
// `later` is B>C's outcome for the hour from that next slot on, and 60 s with p = 1 otherwise.
std::shared_ptr<plan::FunctionEdgeModels> next_slot_models(plan::EdgeCrossing now, plan::EdgeCrossing later) {
  return std::make_shared<plan::FunctionEdgeModels>([=](map::EdgeIndex e, Time t) {
    if (e == 0) return plan::EdgeCrossing{1.0, 1200.0};
    if (t >= kDepart + minutes(15) && t < kDepart + minutes(75)) return later;
    if (t >= kDepart && t < kDepart + minutes(15)) return now;
    return plan::EdgeCrossing{1.0, 60.0};
  });
}

struct Case {
  const char* name;
  plan::EdgeCrossing now, later;  // B>C's in the departure slot and in the next hour
  std::optional<Duration> threshold;
  Duration expected;
};

TEST(TravelAlongTheRoute, TheDepartureSlotOrTheRouteByTheThreshold) {
  const plan::EdgeCrossing open{1.0, 60.0}, slow{1.0, 600.0}, closed{0.0, 60.0};
  const Case cases[] = {
      // Slower when reached: 1200 + 600 s along the route, 1200 + 60 s by the departure slot.
      {"slower, no threshold", open, slow, std::nullopt, seconds(1260)},
      {"slower, above the threshold", open, slow, seconds(60), seconds(1800)},
      {"slower, the difference below the threshold", open, slow, seconds(600), seconds(1260)},
      // Closed for the hour from when it is reached: waiting for it to open pays (4500 + 60 s).
      {"closed when reached, no threshold", open, closed, std::nullopt, seconds(1260)},
      {"closed when reached", open, closed, seconds(60), seconds(4560)},
      // Closed at departure but open when reached: unreachable by the departure slot alone.
      {"open when reached, no threshold", closed, open, std::nullopt, kUnreachable},
      {"open when reached", closed, open, seconds(60), seconds(1260)},
  };
  const map::TopoMap map = plan::testing::small_map({"A", "B", "C"}, {"A>B", "B>C"});
  for (const Case& c : cases) {
    auto models = next_slot_models(c.now, c.later);
    plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
    TravelCache cache(map, models, planner, minutes(15), c.threshold);
    EXPECT_EQ(cache.at_slot(kA, kC, kDepart), c.expected) << c.name;
    EXPECT_EQ(cache.travel(kA, kC, kDepart), c.expected) << c.name;
    EXPECT_LE(cache.lower_bound(kA, kC), cache.travel(kA, kC, kDepart)) << c.name;
    EXPECT_EQ(cache.arrivals_count() > 0, c.threshold.has_value()) << c.name;
  }
}

TEST(TravelAlongTheRoute, IsSearchedAgainWhenTheModelsMoveOnAndKeptForADayBehind) {
  const map::TopoMap map = plan::testing::small_map({"A", "B", "C"}, {"A>B", "B>C"});
  auto models = next_slot_models({1.0, 60.0}, {1.0, 600.0});
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15), seconds(60));
  EXPECT_EQ(cache.at_slot(kA, kC, kDepart), seconds(1800));
  EXPECT_EQ(cache.at_slot(kA, map::NodeIndex{1}, kDepart), seconds(1200));  // the same search
  EXPECT_EQ(cache.route_searches(), 1U);
  models->set([](map::EdgeIndex, Time) { return plan::EdgeCrossing{1.0, 100.0}; });
  EXPECT_EQ(cache.at_slot(kA, kC, kDepart), seconds(200));
  EXPECT_EQ(cache.route_searches(), 2U);
  // Three days of departures from one place: what lies more than a day behind is dropped.
  for (Time t = kDepart; t < kDepart + hours(72); t += minutes(15)) (void)cache.at_slot(kA, kC, t);
  EXPECT_LE(cache.arrivals_count(), 24U * 4U + 1U);
}

RC_GTEST_PROP(TravelAlongTheRoute, IsFifoAndAboveTheLowerBound, ()) {
  const auto seed = *rc::gen::arbitrary<std::uint32_t>();
  const map::TopoMap map = plan::testing::building_map({.rows = 4, .columns = 5, .seed = seed, .door_fraction = 0.4});
  // Strong daily rhythms: the edges' costs move from one 15-minute slot to the next.
  auto models = std::make_shared<plan::FunctionEdgeModels>(plan::testing::daily_models(map, 60.0));
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache cache(map, models, planner, minutes(15), seconds(*rc::gen::inRange(1, 300)));
  const auto a = *rc::gen::inRange<map::NodeIndex>(0, map.node_count());
  const auto b = *rc::gen::inRange<map::NodeIndex>(0, map.node_count());
  const Time t1 = kDepart + seconds(*rc::gen::inRange(0, 86400));
  const Time t2 = t1 + seconds(*rc::gen::inRange(0, 4 * 3600));
  const Duration d1 = cache.travel(a, b, t1), d2 = cache.travel(a, b, t2);
  if (d1 >= kUnreachable || d2 >= kUnreachable) RC_SUCCEED("unreachable");
  RC_ASSERT(t1 + d1 <= t2 + d2 + Duration{1});  // FIFO (1 ms of rounding)
  RC_ASSERT(cache.lower_bound(a, b) <= d1);
  RC_ASSERT(cache.lower_bound(a, b) <= d2);
}

// Small problems on a building with daily rhythms, over travel along the route.
schedule::Problem problem_along_the_route(const TravelCache& cache, const map::TopoMap& map, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  auto pick = [&](std::int64_t lo, std::int64_t hi) {
    return std::uniform_int_distribution<std::int64_t>(lo, hi)(rng);
  };
  schedule::Problem p;
  p.robot = {.location = 0, .time = kDepart};
  std::vector<map::NodeIndex> nodes{
      static_cast<map::NodeIndex>(pick(0, static_cast<std::int64_t>(map.node_count()) - 1))};
  const std::size_t n = 5 + seed % 3;
  for (std::size_t i = 0; i < n; ++i) {
    nodes.push_back(static_cast<map::NodeIndex>(pick(0, static_cast<std::int64_t>(map.node_count()) - 1)));
    const Time release = kDepart + seconds(pick(0, 7200));
    const Duration duration = seconds(pick(60, 300));
    p.tasks.push_back({.id = "t" + std::to_string(i),
                       .release = release,
                       .deadline = release + duration + seconds(pick(1800, 5400)),
                       .duration = duration,
                       .start_location = i + 1,
                       .end_location = i + 1});
  }
  p.travel = std::make_shared<SchedulerTravel>(cache, std::move(nodes));
  return p;
}

TEST(TravelAlongTheRoute, TheDefaultSchedulerAndBruteForceAgree) {
  const map::TopoMap map = plan::testing::building_map({.rows = 4, .columns = 5, .seed = 7, .door_fraction = 0.4});
  auto models = std::make_shared<plan::FunctionEdgeModels>(plan::testing::daily_models(map, 60.0));
  plan::TravelPlanner planner(map, models, {.slot_width = minutes(15)});
  TravelCache along(map, models, planner, minutes(15), seconds(5));
  TravelCache slot(map, models, planner, minutes(15));
  int feasible = 0, differ = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const schedule::Problem p = problem_along_the_route(along, map, seed);
    ASSERT_TRUE(schedule::validate(p).ok()) << seed;
    const auto truth = schedule::testing::brute_force(p);
    const schedule::Schedule ours = schedule::DefaultScheduler{}.solve(p, schedule::NeverStop{});
    EXPECT_TRUE(schedule::check_schedule(p, ours).ok())
        << "seed " << seed << ": " << schedule::check_schedule(p, ours).summary();
    const auto& travel = dynamic_cast<const SchedulerTravel&>(*p.travel);
    for (std::size_t i = 0; i < travel.location_count(); ++i)
      for (std::size_t j = 0; j < travel.location_count(); ++j)
        if (along.travel(travel.node(i), travel.node(j), kDepart) !=
            slot.travel(travel.node(i), travel.node(j), kDepart))
          ++differ;
    if (!truth.objective) {
      EXPECT_EQ(ours.status, schedule::SolveStatus::kInfeasible) << "seed " << seed;
      continue;
    }
    ++feasible;
    EXPECT_EQ(ours.status, schedule::SolveStatus::kOptimal) << "seed " << seed;
    EXPECT_EQ(ours.objective, *truth.objective) << "seed " << seed;
  }
  EXPECT_GE(feasible, 4);
  EXPECT_GE(differ, 1);  // the route's reading matters in these problems
}

// The executor's option reaches its travel: the scheduler's problems read the arrivals along the
// route, and nothing is searched without it.
TEST(TravelAlongTheRoute, TheExecutorsOptionReachesItsTravel) {
  for (const std::optional<Duration> threshold : {std::optional<Duration>{}, std::optional<Duration>{seconds(30)}}) {
    testing::Scenario s(testing::kCalmWorld, ExecutorOptions{.route_threshold = threshold});
    s.fleet().start();
    ASSERT_TRUE(s.fleet().add_task(testing::task("A", "Office", s.at("08:00"), s.at("10:00"), minutes(5)), "test"));
    s.run_until("09:00");
    EXPECT_EQ(s.final_state("A"), "succeeded");
    EXPECT_EQ(s.executor().travel_cache().route_threshold(), threshold);
    EXPECT_EQ(s.executor().travel_cache().route_searches() > 0, threshold.has_value());
  }
}

}  // namespace
}  // namespace rondo::exec
