// Executor::route(): the edges the running navigation expects to take from where the robot is
// (the dashboard draws it), empty when the robot is not on its way.
#include <gtest/gtest.h>

#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

TEST(Route, TheRunningNavigationsRouteEndsAtItsTargetAndShrinksAsTheRobotGoes) {
  ScriptedExecutor s;
  EXPECT_TRUE(s.executor().route().empty());  // nothing to do yet
  ASSERT_TRUE(s.fleet().add_task(task("t", "Office", s.at("08:00"), s.at("12:00"), minutes(5)), "test").ok());
  s.fleet().start();
  s.settle();
  ASSERT_TRUE(s.robot().driving());
  const std::vector<map::EdgeIndex> before = s.executor().route();
  ASSERT_FALSE(before.empty());
  const map::TopoMap m = scenario_map();  // the fixture's map, the same indices
  EXPECT_EQ(m.from_index(before.front()), s.robot().location());
  EXPECT_EQ(m.node(m.to_index(before.back())).name, "Office");
  for (std::size_t i = 1; i < before.size(); ++i) EXPECT_EQ(m.from_index(before[i]), m.to_index(before[i - 1]));
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Office"));
  s.settle();
  EXPECT_TRUE(s.executor().route().empty());  // arrived: acting, not moving
}

}  // namespace
}  // namespace rondo::exec::testing
