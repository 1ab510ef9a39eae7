// Tasks written as co-safe LTL (issue 41, docs/ltl.md) on the scripted robot: the journey follows
// the product policy node by node, never enters a node its formula forbids, goes to another node
// that satisfies it when the way to one is found blocked, keeps what it has done over a preemption
// and a restart, and an unsatisfiable formula is dropped naming the node that blocks it.
//
// Map (every edge both ways, 10 m):
//
//   C ---- Up2 ---- Up1 ---- Up3
//           |                 |
//          Dock --- Short --- Goal
//                     |
//                     B
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>

#include "rondo/store/task_table.h"
#include "scheduling.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

map::TopoMap spec_map() {
  std::vector<map::Node> nodes = {{.name = "Dock", .pose = {0, 0, 0}},  {.name = "Short", .pose = {10, 0, 0}},
                                  {.name = "Goal", .pose = {20, 0, 0}}, {.name = "Up2", .pose = {0, 10, 0}},
                                  {.name = "Up1", .pose = {10, 10, 0}}, {.name = "Up3", .pose = {20, 10, 0}},
                                  {.name = "B", .pose = {10, -10, 0}},  {.name = "C", .pose = {-10, 10, 0}}};
  std::vector<map::Edge> edges;
  for (const auto& [a, b] : std::vector<std::pair<std::string, std::string>>{{"Dock", "Short"},
                                                                             {"Short", "Goal"},
                                                                             {"Dock", "Up2"},
                                                                             {"Up2", "Up1"},
                                                                             {"Up1", "Up3"},
                                                                             {"Up3", "Goal"},
                                                                             {"Short", "B"},
                                                                             {"Up2", "C"}}) {
    edges.push_back({.id = a + "_" + b, .from = a, .to = b, .action = "move_base"});
    edges.push_back({.id = b + "_" + a, .from = b, .to = a, .action = "move_base"});
  }
  return map::TopoMap::build("spec", std::move(nodes), std::move(edges)).value();
}

Task spec_task(ScriptedExecutor& s, const std::string& id, const std::string& formula) {
  Task t;
  t.id = id;
  t.activity = "spec " + formula;
  t.window = TimeWindow{s.at("08:00"), s.at("10:00")};
  t.duration = minutes(2);
  t.spec = formula;
  t.actions = {Action{.name = "look", .args = {}}};
  return t;
}

// The nodes the robot reached, in order, from its calls ("drive A_B +n" answered with success).
class Drive {
 public:
  explicit Drive(ScriptedExecutor& s) : s_(s) {}
  // Answers every edge with success after 20 s, except those in `fail` (failed after 20 s), until
  // the robot asks for something else than an edge; at most `limit` edges.
  void until_still(const std::vector<std::string>& fail = {}, int limit = 40) {
    for (int i = 0; i < limit; ++i) {
      s_.settle();
      if (!s_.robot().driving()) return;
      const std::string call = s_.robot().calls.back();  // "drive X_Y +n"
      const std::string edge = call.substr(6, call.find(' ', 6) - 6);
      s_.clock().run_until(s_.clock().now() + seconds(20));
      const bool failed = std::find(fail.begin(), fail.end(), edge) != fail.end();
      s_.robot().finish_edge(failed ? EdgeOutcome::kFailed : EdgeOutcome::kSucceeded, seconds(20));
      if (!failed) visited.push_back(s_.map().node(s_.robot().location()).name);
    }
  }
  std::vector<std::string> visited;

 private:
  ScriptedExecutor& s_;
};

TEST(SpecTasks, AvoidingANodeTakesTheLongWayAlthoughTheShortWayCrossesIt) {
  ScriptedExecutor s({}, spec_map());
  ASSERT_TRUE(s.fleet().add_task(spec_task(s, "S", "!Short U Goal"), "test").ok());
  s.fleet().start();
  s.settle();
  const Time long_start = s.executor().tasks().at("S").planned_start.value_or(Time{});
  // The planned route (GET /api/v1/robot's, drawn on the dashboard's map) is the long way.
  std::vector<std::string> planned;
  for (map::EdgeIndex e : s.executor().route()) planned.push_back(s.map().edge(e).id);
  EXPECT_EQ(planned, (std::vector<std::string>{"Dock_Up2", "Up2_Up1", "Up1_Up3", "Up3_Goal"}));
  Drive d(s);
  d.until_still();
  EXPECT_EQ(d.visited, (std::vector<std::string>{"Up2", "Up1", "Up3", "Goal"}));
  EXPECT_EQ(s.robot().calls.back(), "act look");  // its actions run where the formula is satisfied
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("S"), "succeeded");
  EXPECT_THAT(s.reason_of("S", "navigating"), ::testing::HasSubstr("route Dock > Up2 > Up1 > Up3 > Goal"));
  // Without the formula, the short way; the scheduler priced each by its own journey.
  ScriptedExecutor plain({}, spec_map());
  ASSERT_TRUE(plain.fleet().add_task(spec_task(plain, "P", "F Goal"), "test").ok());
  plain.fleet().start();
  plain.settle();
  const Time short_start = plain.executor().tasks().at("P").planned_start.value_or(Time{});
  EXPECT_GT(short_start, plain.at("08:00"));
  EXPECT_GT(long_start - s.at("08:00"), (short_start - plain.at("08:00")) * 3 / 2);  // 4 edges against 2
  Drive p(plain);
  p.until_still();
  EXPECT_EQ(p.visited, (std::vector<std::string>{"Short", "Goal"}));
}

// The scheduler's travel to a spec task is FIFO: leaving later never arrives sooner.
RC_GTEST_PROP(SpecPrice, LeavingLaterNeverArrivesSooner, ()) {
  const auto slots = *rc::gen::inRange<std::size_t>(1, 6);
  SpecPrice price{.location = 0, .first_slot = Time{hours(1000)}, .slot_width = minutes(15), .seconds = {}};
  for (std::size_t k = 0; k < slots; ++k) price.seconds.push_back({static_cast<double>(*rc::gen::inRange(0, 4000))});
  price.repair_fifo();
  const auto a = *rc::gen::inRange<std::int64_t>(-1000, 6000);
  const auto b = *rc::gen::inRange<std::int64_t>(a, 6001);
  const Time ta = price.first_slot + seconds(a), tb = price.first_slot + seconds(b);
  RC_ASSERT(ta + price.travel(0, ta) <= tb + price.travel(0, tb) + milliseconds(1));
  RC_ASSERT(price.lower_bound(0) <= price.travel(0, ta));
}

TEST(SpecTasks, WhenTheWayToBIsFoundBlockedTheRobotGoesToC) {
  ScriptedExecutor s({}, spec_map());
  ASSERT_TRUE(s.fleet().add_task(spec_task(s, "S", "F B | F C"), "test").ok());
  s.fleet().start();
  Drive d(s);
  d.until_still({"Short_B"});
  ASSERT_FALSE(d.visited.empty());
  EXPECT_EQ(d.visited.front(), "Short");  // B is nearer: the robot heads for it first
  EXPECT_EQ(d.visited.back(), "C");       // ... and, Short_B found blocked, goes to C
  EXPECT_EQ(std::count(d.visited.begin(), d.visited.end(), "B"), 0);
  EXPECT_EQ(s.robot().calls.back(), "act look");
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("S"), "succeeded");
  EXPECT_THAT(s.reason_of("S", "edge"), ::testing::HasSubstr("Short_B found blocked"));
}

TEST(SpecTasks, APreemptedSpecTaskResumesWithoutRevisitingWhatItHadDone) {
  ScriptedExecutor s({}, spec_map());
  ASSERT_TRUE(s.fleet().add_task(spec_task(s, "S", "F B & F C"), "test").ok());
  s.fleet().start();
  Drive d(s);
  // To B first (nearer), then an on-demand task at Goal takes the robot.
  for (int i = 0; i < 2; ++i) {
    s.settle();
    ASSERT_TRUE(s.robot().driving());
    s.clock().run_until(s.clock().now() + seconds(20));
    s.robot().finish_edge(EdgeOutcome::kSucceeded, seconds(20));
  }
  ASSERT_EQ(s.map().node(s.robot().location()).name, "B");
  s.settle();
  Task od = on_demand("OD", "Goal", minutes(1));
  ASSERT_TRUE(s.fleet().add_task(od, "request").ok());
  s.settle();
  ASSERT_TRUE(s.robot().asked("cancel"));  // the spec task's edge under way, for the on-demand task
  EXPECT_EQ(s.state("S"), "queued");
  EXPECT_EQ(s.executor().tasks().at("S").spec_place, "");
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Goal"));
  s.settle();
  ASSERT_EQ(s.robot().calls.back(), "act talk");
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  ASSERT_EQ(s.state("OD"), "succeeded");
  // S goes on from Goal: B stays done, only C is left.
  Drive rest(s);
  rest.until_still();
  EXPECT_EQ(std::count(rest.visited.begin(), rest.visited.end(), "B"), 0);
  EXPECT_EQ(rest.visited.back(), "C");
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("S"), "succeeded");
}

TEST(SpecTasks, ItsAutomatonStateSurvivesARestart) {
  ScriptedExecutor s({}, spec_map());
  ASSERT_TRUE(s.fleet().add_task(spec_task(s, "S", "F B & F C"), "test").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("B"));
  ASSERT_TRUE(store::get_task(s.store(), "S").value().progress.contains("spec_state"));
  ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
  Drive rest(s);
  rest.until_still();
  EXPECT_EQ(std::count(rest.visited.begin(), rest.visited.end(), "B"), 0);
  ASSERT_FALSE(rest.visited.empty());
  EXPECT_EQ(rest.visited.back(), "C");
  s.robot().finish_action(ActionOutcome::kSucceeded);
  s.settle();
  EXPECT_EQ(s.state("S"), "succeeded");
}

TEST(SpecTasks, AnUnsatisfiableSpecIsRefusedNamingTheNodeThatBlocksIt) {
  ScriptedExecutor s({}, spec_map());
  // B hangs off Short only: "reach B without passing Short" cannot be done.
  ASSERT_TRUE(s.fleet().add_task(spec_task(s, "S", "!Short U B"), "test").ok());
  s.fleet().start();
  s.settle();
  EXPECT_EQ(s.state("S"), "dropped");
  EXPECT_EQ(s.code_of("S", "dropped"), "spec unsatisfiable");
  EXPECT_THAT(s.reason_of("S", "dropped"), ::testing::HasSubstr("'Short'"));
  EXPECT_FALSE(s.robot().driving());
}

}  // namespace
}  // namespace rondo::exec::testing
