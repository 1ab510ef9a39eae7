// Allocation by the fleet scheduler (FleetSchedulerAllocator) on scripted robots: a task at a
// robot's place, a named robot, an action only some robots run, a delivery's halves as one pair, a
// robot whose schedule is full, on-demand tasks by the greedy's rule; every plan it builds passes
// check_fleet_plan, and on small batches it is the brute force's optimum; property: its answers
// are always among each unit's eligible robots, and the same for the same seed.
#include <gtest/gtest.h>
#include <rapidcheck.h>
#include <rapidcheck/gtest.h>

#include <random>

#include "fleet_brute_force.h"
#include "fleet_fixture.h"
#include "rondo/fleet/fleet_scheduler_allocator.h"
#include "rondo/schedule/fleet_checker.h"

namespace rondo::fleet::testing {
namespace {

using exec::testing::task;

// A fleet whose allocator is the fleet scheduler, kept at hand to read its last problem and plan.
struct SchedulerFleet {
  explicit SchedulerFleet(const std::vector<ScriptedFleet::RobotAt>& robots,
                          FleetSchedulerAllocatorOptions options = {})
      : fleet(robots, [this, options] {
          auto a = std::make_unique<FleetSchedulerAllocator>(options);
          allocator = a.get();
          return a;
        }) {}
  // The last plan passes the independent checker.
  void expect_checked() const {
    ASSERT_TRUE(allocator->last_problem() && allocator->last_plan());
    const schedule::FleetCheckReport r =
        schedule::check_fleet_plan(allocator->last_problem()->problem, *allocator->last_plan());
    EXPECT_TRUE(r.ok()) << r.summary();
  }
  FleetSchedulerAllocator* allocator = nullptr;
  ScriptedFleet fleet;
};

Task with_action(Task t, const std::string& action) {
  t.actions = {Action{.name = action, .args = {}}};
  return t;
}

Task delivery_half(const std::string& job, const std::string& id, const std::string& node, DeliveryRole role, Time from,
                   Time to) {
  Task t = task(id, node, from, to, minutes(2));
  t.actions = {Action{.name = role == DeliveryRole::kPickup ? "load" : "unload", .args = {{"object", "book"}}}};
  t.delivery = Delivery{.job = job, .role = role, .object = "book", .appearance = "a green book"};
  return t;
}

// Job "job1": a book picked up at the Kitchen ("p") and dropped at the Office ("d"), 08:00 to 12:00.
std::vector<Task> kitchen_to_office(const ScriptedFleet& f) {
  return {delivery_half("job1", "p", "Kitchen", DeliveryRole::kPickup, f.at("08:00"), f.at("12:00")),
          delivery_half("job1", "d", "Office", DeliveryRole::kDrop, f.at("08:00"), f.at("12:00"))};
}

TEST(FleetSchedulerAllocator, ATaskGoesToTheRobotStandingAtItsPlace) {
  SchedulerFleet s({{"r1", "Dock"}, {"r2", "Office"}, {"r3", "Lab"}});
  ScriptedFleet& f = s.fleet;
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_task(task("a", "Office", f.at("08:00"), f.at("12:00"), minutes(5)), "test").ok());
  EXPECT_EQ(f.robot_of("a"), "r2");
  s.expect_checked();
  ASSERT_TRUE(f.fleet().add_task(task("b", "Lab", f.at("08:00"), f.at("12:00"), minutes(5)), "test").ok());
  EXPECT_EQ(f.robot_of("b"), "r3");
  s.expect_checked();
  f.settle();
  EXPECT_TRUE(f.robot(1).acting());
  EXPECT_TRUE(f.robot(2).acting());
  EXPECT_FALSE(f.robot(0).busy());
}

TEST(FleetSchedulerAllocator, ANamedRobotIsPinnedAndTheOthersSeeItsTask) {
  SchedulerFleet s({{"r1", "Office"}, {"r2", "Dock"}});
  ScriptedFleet& f = s.fleet;
  f.fleet().start();
  // "a" names r2 although r1 stands there; "b", in the same batch at the same place, is free to go
  // anywhere and goes to r1, which stands there.
  Task a = task("a", "Office", f.at("08:00"), f.at("12:00"), minutes(5));
  a.robot = "r2";
  ASSERT_TRUE(f.fleet().add_tasks({a, task("b", "Office", f.at("08:00"), f.at("12:00"), minutes(5))}, "test").ok());
  EXPECT_EQ(f.robot_of("a"), "r2");
  EXPECT_EQ(f.robot_of("b"), "r1");
  s.expect_checked();
  const AllocationProblem& p = *s.allocator->last_problem();
  ASSERT_EQ(p.unit_tasks.size(), 2u);
  EXPECT_EQ(p.problem.tasks[p.unit_tasks[0].front()].pinned_robot, std::optional<std::size_t>{1});
}

TEST(FleetSchedulerAllocator, AnActionSomeRobotsRunKeepsTheUnitAmongThem) {
  SchedulerFleet s({{"r1", "Office"}, {"r2", "Dock"}, {"r3", "Kitchen"}});
  ScriptedFleet& f = s.fleet;
  f.robot(0).actions = exec::ActionSupport{.robot = "r1", .actions = {"work"}};
  f.robot(1).actions = exec::ActionSupport{.robot = "r2", .actions = {"work", "mop"}};
  f.robot(2).actions = exec::ActionSupport{.robot = "r3", .actions = {"work", "mop"}};
  f.fleet().start();
  // r1 stands at the Office but does not mop; r2 is nearer than r3 (Dock -- Hall -- Office).
  ASSERT_TRUE(f.fleet()
                  .add_tasks({with_action(task("m", "Office", f.at("08:00"), f.at("12:00"), minutes(5)), "mop"),
                              with_action(task("w", "Office", f.at("08:00"), f.at("12:00"), minutes(5)), "work")},
                             "test")
                  .ok());
  EXPECT_NE(f.robot_of("m"), "r1");
  EXPECT_EQ(f.robot_of("w"), "r1");
  s.expect_checked();
  const AllocationProblem& p = *s.allocator->last_problem();
  const std::string& action = p.problem.tasks[p.unit_tasks[0].front()].action;
  EXPECT_FALSE(action.empty());
  EXPECT_TRUE(p.problem.robots[0].actions.empty());  // r1 lists none of the tokens
  EXPECT_EQ(p.problem.robots[1].actions, std::vector<std::string>{action});
  EXPECT_EQ(p.problem.robots[2].actions, std::vector<std::string>{action});
}

TEST(FleetSchedulerAllocator, ADeliveryIsOnePairOnOneRobot) {
  SchedulerFleet s({{"r1", "Kitchen"}, {"r2", "Office"}});
  ScriptedFleet& f = s.fleet;
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_tasks(kitchen_to_office(f), "test").ok());
  EXPECT_EQ(f.robot_of("p"), f.robot_of("d"));
  s.expect_checked();
  const AllocationProblem& p = *s.allocator->last_problem();
  ASSERT_EQ(p.unit_tasks.size(), 1u);
  ASSERT_EQ(p.unit_tasks[0].size(), 2u);
  const auto& pickup = p.problem.tasks[p.unit_tasks[0][0]].task.transfer;
  const auto& drop = p.problem.tasks[p.unit_tasks[0][1]].task.transfer;
  ASSERT_TRUE(pickup && drop);
  EXPECT_EQ(pickup->action, schedule::ItemAction::kPickup);
  EXPECT_EQ(drop->action, schedule::ItemAction::kDrop);
  EXPECT_EQ(pickup->job, "job1");
}

TEST(FleetSchedulerAllocator, ADeliveryGoesToARobotThatRunsBothHalves) {
  SchedulerFleet s({{"r1", "Kitchen"}, {"r2", "Dock"}});
  ScriptedFleet& f = s.fleet;
  // r1 stands at the pickup and loads, but only r2 unloads too.
  f.robot(0).actions = exec::ActionSupport{.robot = "r1", .actions = {"work", "load"}};
  f.robot(1).actions = exec::ActionSupport{.robot = "r2", .actions = {"work", "load", "unload"}};
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_tasks(kitchen_to_office(f), "test").ok());
  EXPECT_EQ(f.robot_of("p"), "r2");
  EXPECT_EQ(f.robot_of("d"), "r2");
}

TEST(FleetSchedulerAllocator, ARobotWithAFullScheduleKeepsItsTasksAndTheNewOneGoesElsewhere) {
  SchedulerFleet s({{"r1", "Office"}, {"r2", "Dock"}});
  ScriptedFleet& f = s.fleet;
  f.fleet().start();
  // r1's morning at the Office, 09:00 to 11:00, named to it.
  std::vector<Task> morning;
  for (int i = 0; i < 4; ++i) {
    Task t = task("full" + std::to_string(i), "Office", f.at("09:00") + minutes(30 * i),
                  f.at("09:00") + minutes(30 * (i + 1)), minutes(30));
    t.robot = "r1";
    morning.push_back(t);
  }
  ASSERT_TRUE(f.fleet().add_tasks(morning, "test").ok());
  ASSERT_EQ(f.fleet().robot().activity().planned.size(), 4u);
  // A task at the Office that must be done between 09:00 and 10:00: r1 has no room for it.
  ASSERT_TRUE(f.fleet().add_task(task("new", "Office", f.at("09:00"), f.at("10:00"), minutes(10)), "test").ok());
  EXPECT_EQ(f.robot_of("new"), "r2");
  s.expect_checked();
  // Its planned tasks were in the problem, pinned to it, and stayed there.
  const AllocationProblem& p = *s.allocator->last_problem();
  EXPECT_EQ(p.planned_tasks, 4u);
  for (std::size_t i = 0; i < p.planned_tasks; ++i)
    EXPECT_EQ(p.problem.tasks[i].pinned_robot, std::optional<std::size_t>{0});
  EXPECT_EQ(s.allocator->last_plan()->routes[0].size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(f.robot_of("full" + std::to_string(i)), "r1");
}

TEST(FleetSchedulerAllocator, AnOnDemandTaskGoesToTheRobotThatCanBeThereSoonest) {
  SchedulerFleet s({{"r1", "Dock"}, {"r2", "Kitchen"}});
  ScriptedFleet& f = s.fleet;
  f.fleet().start();
  ASSERT_TRUE(f.fleet().add_task(exec::testing::on_demand("call", "Kitchen", minutes(2)), "test").ok());
  EXPECT_EQ(f.robot_of("call"), "r2");
  EXPECT_FALSE(s.allocator->last_problem());  // the solver was not asked
}

TEST(FleetSchedulerAllocator, ATaskThePlanCannotHoldGoesWhereTheGreedyPutsIt) {
  // A task whose window cannot hold its work (validated away from the problem) is not in it.
  SchedulerFleet s({{"r1", "Dock"}, {"r2", "Office"}});
  ScriptedFleet& f = s.fleet;
  f.fleet().start();
  Task late = task("late", "Office", f.at("08:00"), f.at("08:01"), minutes(5));
  const exec::Executor* r1 = &f.fleet().robot();
  const exec::Executor* r2 = f.fleet().find_robot("r2");
  const std::vector<AllocationUnit> units{{.tasks = {&late}, .eligible = {0, 1}}};
  const std::vector<Allocation> chosen = s.allocator->allocate(units, {r1, r2}, f.fleet().building());
  const std::vector<Allocation> greedy = GreedyAllocator().allocate(units, {r1, r2}, f.fleet().building());
  ASSERT_EQ(chosen.size(), 1u);
  EXPECT_EQ(chosen[0].robot, greedy[0].robot);
  EXPECT_EQ(chosen[0].fits, greedy[0].fits);
  EXPECT_EQ(chosen[0].why, greedy[0].why);
}

// Small batches on two scripted robots, some with work planned: the plan the allocation builds is
// as good as the slow, obviously correct brute force's on the same problem.
TEST(FleetSchedulerAllocator, SmallAllocationsAreOptimal) {
  const std::vector<std::string> places{"Dock", "Hall", "Office", "Kitchen", "Lab"};
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    std::mt19937_64 rng(seed);
    const auto pick = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
    SchedulerFleet s(
        {{"r1", places[static_cast<std::size_t>(pick(0, 4))]}, {"r2", places[static_cast<std::size_t>(pick(0, 4))]}});
    ScriptedFleet& f = s.fleet;
    f.fleet().start();
    for (const std::string batch : {"a", "b"}) {
      std::vector<Task> tasks;
      for (int i = 0, n = pick(1, 3); i < n; ++i) {
        const Time release = f.at("08:30") + minutes(pick(0, 60));
        tasks.push_back(task(batch + std::to_string(i), places[static_cast<std::size_t>(pick(0, 4))], release,
                             release + minutes(pick(8, 60)), minutes(pick(1, 6))));
      }
      ASSERT_TRUE(f.fleet().add_tasks(tasks, "test").ok());
      s.expect_checked();
      const schedule::FleetProblem& p = s.allocator->last_problem()->problem;
      const auto truth = schedule::testing::FleetBruteForce(p).solve();
      ASSERT_TRUE(truth);
      EXPECT_NEAR(s.allocator->last_plan()->objective, truth->first, 1e-6) << "seed " << seed << " batch " << batch;
    }
  }
}

// Random batches on three scripted robots with random actions: every answer is one of the unit's
// eligible robots, the same again for the same seed, and the plan passes the checker.
RC_GTEST_PROP(FleetSchedulerAllocatorProperty, AnswersAreEligibleDeterministicAndChecked, ()) {
  const std::vector<std::string> places{"Dock", "Hall", "Office", "Kitchen", "Lab"};
  const std::vector<std::string> actions{"work", "mop", "load", "unload"};
  const std::size_t count = *rc::gen::inRange<std::size_t>(1, 7);
  const std::uint64_t seed = *rc::gen::inRange<std::uint64_t>(1, 1000);
  std::vector<ScriptedFleet::RobotAt> at;
  for (int r = 0; r < 3; ++r) at.push_back({"r" + std::to_string(r + 1), *rc::gen::elementOf(places)});
  // Which actions each robot runs (each runs "work", so every task has a robot).
  std::vector<std::vector<std::string>> runs(3, {"work"});
  for (auto& r : runs)
    for (std::size_t a = 1; a < actions.size(); ++a)
      if (*rc::gen::arbitrary<bool>()) r.push_back(actions[a]);
  std::vector<Task> first, second;
  const Time eight = TimeZone::named("Europe/London").value().parse_time("2026-11-23T08:00").value();
  int job = 0;
  for (std::vector<Task>* batch : {&first, &second})
    for (std::size_t i = 0; i < count; ++i) {
      const Time release = eight + minutes(*rc::gen::inRange(0, 120));
      const Time deadline = release + minutes(*rc::gen::inRange(10, 180));
      const std::string id = (batch == &first ? "a" : "b") + std::to_string(i);
      if (*rc::gen::inRange(0, 4) == 0) {
        const std::string name = "job" + std::to_string(job++);
        batch->push_back(delivery_half(name, id + "p", *rc::gen::elementOf(places), DeliveryRole::kPickup, release,
                                       deadline + minutes(30)));
        batch->push_back(delivery_half(name, id + "d", *rc::gen::elementOf(places), DeliveryRole::kDrop, release,
                                       deadline + minutes(30)));
        continue;
      }
      Task t = with_action(task(id, *rc::gen::elementOf(places), release, deadline, minutes(*rc::gen::inRange(1, 9))),
                           actions[*rc::gen::inRange<std::size_t>(0, 2)]);  // work or mop
      if (*rc::gen::inRange(0, 5) == 0) t.robot = at[*rc::gen::inRange<std::size_t>(0, 3)].name;
      batch->push_back(t);
    }
  // The same fleet twice: the second batch's allocation with the first batch planned.
  std::vector<std::vector<std::string>> robots_of;
  for (int run = 0; run < 2; ++run) {
    SchedulerFleet s(at, {.seed = seed});
    ScriptedFleet& f = s.fleet;
    for (std::size_t r = 0; r < 3; ++r)
      f.robot(r).actions = exec::ActionSupport{.robot = at[r].name, .actions = runs[r]};
    f.fleet().start();
    std::vector<std::string> robots;
    for (const std::vector<Task>* batch : {&first, &second}) {
      // A task no robot runs (mop, or a delivery's halves, with no robot listing them) is refused.
      std::vector<Task> runnable;
      for (const Task& t : *batch) {
        const bool anyone = std::any_of(runs.begin(), runs.end(), [&](const auto& r) {
          return std::find(r.begin(), r.end(), t.actions.front().name) != r.end();
        });
        const std::size_t named = t.robot.empty() ? 3 : static_cast<std::size_t>(t.robot[1] - '1');
        const bool its_robot = named == 3 || std::find(runs[named].begin(), runs[named].end(),
                                                       t.actions.front().name) != runs[named].end();
        if (anyone && its_robot) runnable.push_back(t);
      }
      // Halves of a job both or neither, and jobs only when one robot both loads and unloads.
      const bool carried = std::any_of(runs.begin(), runs.end(), [](const auto& r) {
        return std::find(r.begin(), r.end(), "load") != r.end() && std::find(r.begin(), r.end(), "unload") != r.end();
      });
      std::erase_if(runnable, [&](const Task& t) {
        if (!t.delivery) return false;
        return !carried || std::count_if(runnable.begin(), runnable.end(), [&](const Task& o) {
                             return o.delivery && o.delivery->job == t.delivery->job;
                           }) != 2;
      });
      if (runnable.empty()) continue;
      const Status ok = f.fleet().add_tasks(runnable, "test");
      RC_ASSERT(ok.ok());
      for (const Task& t : runnable) {
        const std::string& robot = f.robot_of(t.id);
        const std::size_t r = static_cast<std::size_t>(robot[1] - '1');
        RC_ASSERT(std::find(runs[r].begin(), runs[r].end(), t.actions.front().name) != runs[r].end());
        if (!t.robot.empty()) RC_ASSERT(robot == t.robot);
        robots.push_back(robot);
      }
      if (s.allocator->last_problem()) {
        const schedule::FleetCheckReport report =
            schedule::check_fleet_plan(s.allocator->last_problem()->problem, *s.allocator->last_plan());
        RC_ASSERT(report.ok());
      }
    }
    robots_of.push_back(std::move(robots));
  }
  RC_ASSERT(robots_of[0] == robots_of[1]);
}

}  // namespace
}  // namespace rondo::fleet::testing
