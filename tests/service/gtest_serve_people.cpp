// `rondo serve`'s simulated people: their requests reach the executor when they fall due, day
// after day, as in `rondo run` (on a simulated clock here, so the test takes no real time).
#include <gtest/gtest.h>

#include <set>

#include "deployment.h"
#include "deployment_parts.h"
#include "rondo/exec/clock.h"
#include "rondo/exec/executor.h"
#include "rondo/fleet/fleet.h"
#include "rondo/sim/sim_robot.h"
#include "rondo/store/store.h"
#include "serve_session.h"
#include "source_dir.h"
#include "test_files.h"

namespace rondo::test {
namespace {

TEST(ServePeople, RequestsArriveWhenDueEveryDay) {
  auto d = app::load_deployment(rondo::testing::source_dir() / "examples/g4s/deployment.yaml");
  ASSERT_TRUE(d.ok()) << d.error().message;
  auto parts = app::load_parts(*d);
  ASSERT_TRUE(parts.ok()) << parts.error().message;
  ASSERT_TRUE(parts->people.has_value());
  const auto dir = fresh_dir("rondo-service-test", "people");
  auto db = store::Store::open(dir / "rondo.sqlite", {.sync_commits = false});
  ASSERT_TRUE(db.ok());
  const Time monday = d->zone.at(d->start, Duration{0});
  exec::SimClock clock(monday);
  sim::SimRobot robot(clock, parts->map, *parts->world, {.start = parts->dock, .dock = parts->dock, .seed = 1});
  exec::ExecutorOptions options = d->executor;
  options.dock = parts->dock;
  fleet::Fleet fleet(clock, parts->map, *db, d->zone, options);
  exec::Executor& executor = fleet.add_robot(robot, options);
  fleet.start();
  sim::Rng rng(5);
  app::schedule_people(clock, fleet, *parts->people, rng, d->zone, clock.now());

  const auto requests_added_before = [&](Time t) {
    int n = 0;
    for (const auto& [id, r] : executor.tasks())
      if (r.source == "request") {
        EXPECT_LE(r.added, t);
        ++n;
      }
    return n;
  };
  clock.run_until(monday + hours(24));
  const int first_day = requests_added_before(clock.now());
  EXPECT_GT(first_day, 0);
  clock.run_until(monday + hours(48));
  EXPECT_GT(requests_added_before(clock.now()), first_day);  // the next day's were drawn at midnight
  // Each arrived at its own time, not all at once.
  std::set<Time> times;
  for (const auto& [id, r] : executor.tasks())
    if (r.source == "request") times.insert(r.added);
  EXPECT_GT(times.size(), 1u);
}

}  // namespace
}  // namespace rondo::test
