// The checker catches each kind of broken schedule (table-driven: one mutation per rule).
#include "rondo/schedule/checker.h"

#include <functional>

#include <gtest/gtest.h>

#include "rondo/schedule/default_scheduler.h"

namespace rondo::schedule {
namespace {

const Time kT0 = Time{} + hours(9);

// Three places 60 s apart; a pickup at 1, a drop at 2, a visit at 1; capacity 1.
Problem delivery_problem() {
  Problem p;
  p.travel = std::make_shared<MatrixTravel>(
      MatrixTravel::create(3, {Duration{0}, seconds(60), seconds(60), seconds(60), Duration{0}, seconds(60),
                               seconds(60), seconds(60), Duration{0}})
          .value());
  p.robot.time = kT0;
  p.robot.capacity = 1;
  auto task = [&](std::string id, LocationIndex at, std::optional<ItemTransfer> x) {
    ProblemTask t;
    t.id = std::move(id);
    t.release = kT0;
    t.deadline = kT0 + minutes(30);
    t.duration = seconds(30);
    t.start_location = t.end_location = at;
    t.transfer = std::move(x);
    return t;
  };
  p.tasks.push_back(task("pick", 1, ItemTransfer{"j", ItemAction::kPickup, "green book", 1}));
  p.tasks.push_back(task("drop", 2, ItemTransfer{"j", ItemAction::kDrop, "green book", 1}));
  p.tasks.push_back(task("visit", 1, std::nullopt));
  return p;
}

TEST(Checker, AcceptsTheSolversScheduleAndRejectsEachBrokenRule) {
  const Problem base = delivery_problem();
  const Schedule good = DefaultScheduler{}.solve(base, NeverStop{});
  ASSERT_EQ(good.status, SolveStatus::kOptimal);
  ASSERT_TRUE(check_schedule(base, good).ok()) << check_schedule(base, good).summary();

  struct Case {
    std::string name;
    std::function<void(Problem&, Schedule&)> mutate;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"objective misreported", [](Problem&, Schedule& s) { s.objective += seconds(1); }, "reported objective"},
      {"task missing", [](Problem&, Schedule& s) { s.entries.pop_back(); }, "neither scheduled nor dropped"},
      {"task twice", [](Problem&, Schedule& s) { s.entries.push_back(s.entries.back()); }, "appears 2 times"},
      {"starts before release",
       [](Problem& p, Schedule& s) { p.tasks[s.entries[0].task].release = s.entries[0].start + seconds(1); },
       "before its release"},
      {"misses deadline",
       [](Problem& p, Schedule& s) { p.tasks[s.entries[2].task].deadline = s.entries[2].end - seconds(1); },
       "misses its deadline"},
      {"travel too short", [](Problem&, Schedule& s) { s.entries[0].arrival -= seconds(1); }, "travel takes"},
      {"overlap",
       [](Problem&, Schedule& s) {
         s.entries[1].depart -= seconds(40);
         s.entries[1].arrival -= seconds(40);
         s.entries[1].start -= seconds(40);
         s.entries[1].end -= seconds(40);
       },
       "overlaps"},
      {"drop before pickup", [](Problem&, Schedule& s) { std::swap(s.entries[0], s.entries[2]); }, "not on board"},
      {"precedence",
       [](Problem& p, Schedule& s) { p.tasks[s.entries[0].task].after.push_back(s.entries[2].task); },
       "must end first"},
      {"capacity", [](Problem& p, Schedule&) { p.robot.on_board.push_back({"other", "", 1}); }, "exceeds capacity"},
      {"same-looking",
       [](Problem& p, Schedule&) {
         p.robot.capacity = 0;
         p.robot.on_board.push_back({"other", "green book", 1});
       },
       "looks like 'green book'"},
      {"dropped without reason",
       [](Problem&, Schedule& s) {
         s.dropped.push_back({s.entries.back().task, "", DropCause::kDoesNotFit});
         s.objective -= s.entries.back().end - kT0;
         s.entries.pop_back();
       },
       "has no reason"},
  };
  for (const auto& c : cases) {
    Problem broken_problem = base;
    Schedule broken = good;
    c.mutate(broken_problem, broken);
    const CheckReport r = check_schedule(broken_problem, broken);
    ASSERT_FALSE(r.ok()) << c.name;
    EXPECT_NE(r.summary().find(c.expected), std::string::npos) << c.name << ": " << r.summary();
  }
}

}  // namespace
}  // namespace rondo::schedule
