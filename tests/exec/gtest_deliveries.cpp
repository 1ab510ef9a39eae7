// Delivery jobs in the executor (MISSION.md §5), on the scripted robot: precedence, interleaving,
// look-alike objects, what is on board, a failed pickup, cancelling a job, and an object taken
// back when its drop does not happen. Each runs twice: with every task kept in memory (rondo run)
// and with finished tasks leaving it for the store (rondo serve's forget_finished), the same.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "rondo/exec/executor.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

Task half(const std::string& id, const std::string& job, DeliveryRole role, const std::string& node,
          const std::string& object, const std::string& appearance, Time release, Time deadline) {
  Task t = task(id, node, release, deadline, minutes(2));
  t.actions = {Action{.name = role == DeliveryRole::kPickup ? "load" : "unload", .args = {{"object", object}}}};
  t.delivery = Delivery{.job = job, .role = role, .object = object, .appearance = appearance, .load = 1};
  return t;
}

class Courier : public ScriptedExecutor {
 public:
  using ScriptedExecutor::ScriptedExecutor;
  Courier(ExecutorOptions options, bool forget) : ScriptedExecutor(with_forget(options, forget)) {}
  static ExecutorOptions with_forget(ExecutorOptions o, bool forget) {
    o.forget_finished = forget;
    return o;
  }
  // Both halves of a job, open all morning.
  void job(const std::string& name, const std::string& from, const std::string& to, const std::string& object,
           const std::string& looks = "") {
    ASSERT_TRUE(
        fleet()
            .add_tasks(
                {half(name + "-pickup", name, DeliveryRole::kPickup, from, object, looks, at("08:00"), at("12:00")),
                 half(name + "-drop", name, DeliveryRole::kDrop, to, object, looks, at("08:00"), at("12:00"))},
                "test")
            .ok());
  }
  Time planned(const std::string& id) { return executor().tasks().at(id).planned_start.value(); }
  // From memory, or from the store once it has left memory.
  TaskRecord record(const std::string& id) { return executor().task(id).value().value(); }
  // Drives to `node` and answers its one action.
  void serve(const std::string& node, ActionOutcome outcome = ActionOutcome::kSucceeded) {
    ASSERT_NO_FATAL_FAILURE(drive_to(node));
    settle();
    ASSERT_TRUE(robot().acting()) << "no action at " << node;
    robot().finish_action(outcome);
    settle();
  }
};

class Deliveries : public ::testing::TestWithParam<bool> {};
INSTANTIATE_TEST_SUITE_P(KeptAndForgotten, Deliveries, ::testing::Bool(),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "Forgotten" : "Kept"; });

TEST_P(Deliveries, PickupsComeBeforeTheirDropsAndInterleaveWhenThatIsFaster) {
  Courier c({}, GetParam());
  ASSERT_NO_FATAL_FAILURE(c.job("letter", "Office", "Kitchen", "letter"));
  ASSERT_NO_FATAL_FAILURE(c.job("book", "Lab", "Kitchen", "book"));
  c.fleet().start();
  for (const char* j : {"letter", "book"})
    EXPECT_LT(c.planned(std::string(j) + "-pickup"), c.planned(std::string(j) + "-drop")) << j;
  // Office, Lab, Kitchen, Kitchen beats Office, Kitchen, Lab, Kitchen: both pickups first.
  const Time last_pickup = std::max(c.planned("letter-pickup"), c.planned("book-pickup"));
  const Time first_drop = std::min(c.planned("letter-drop"), c.planned("book-drop"));
  EXPECT_LT(last_pickup, first_drop);
}

TEST_P(Deliveries, TwoObjectsThatLookTheSameAreNeverOnBoardTogether) {
  Courier c({}, GetParam());
  ASSERT_NO_FATAL_FAILURE(c.job("a", "Office", "Kitchen", "red letter", "red letter"));
  ASSERT_NO_FATAL_FAILURE(c.job("b", "Lab", "Kitchen", "red letter", "red letter"));
  c.fleet().start();
  const bool a_first = c.planned("a-pickup") < c.planned("b-pickup");
  const std::string first = a_first ? "a" : "b", second = a_first ? "b" : "a";
  EXPECT_LT(c.planned(first + "-drop"), c.planned(second + "-pickup"));
}

TEST_P(Deliveries, WhatIsOnBoardFollowsThePickupAndTheDrop) {
  Courier c({}, GetParam());
  ASSERT_NO_FATAL_FAILURE(c.job("letter", "Office", "Kitchen", "letter"));
  c.fleet().start();
  EXPECT_TRUE(c.executor().on_board().empty());
  ASSERT_NO_FATAL_FAILURE(c.serve("Office"));
  EXPECT_EQ(c.state("letter-pickup"), "succeeded");
  EXPECT_EQ(c.executor().tasks().contains("letter-pickup"), !GetParam());  // forgotten: only in the store
  ASSERT_EQ(c.executor().on_board().size(), 1u);
  EXPECT_EQ(c.executor().on_board()[0].object, "letter");
  ASSERT_NO_FATAL_FAILURE(c.serve("Kitchen"));
  EXPECT_EQ(c.state("letter-drop"), "succeeded");
  EXPECT_TRUE(c.executor().on_board().empty());
}

TEST_P(Deliveries, AFailedPickupFailsItsDrop) {
  Courier c({}, GetParam());
  ASSERT_NO_FATAL_FAILURE(c.job("letter", "Office", "Kitchen", "letter"));
  c.fleet().start();
  ASSERT_NO_FATAL_FAILURE(c.serve("Office", ActionOutcome::kFailed));
  EXPECT_EQ(c.state("letter-pickup"), "failed");
  EXPECT_EQ(c.state("letter-drop"), "failed");
  EXPECT_EQ(last_event_field(c.store(), "letter-drop", "failed", &store::Event::code), "pickup failed");
  EXPECT_THAT(c.record("letter-drop").reason, HasSubstr("letter-pickup failed"));
}

TEST_P(Deliveries, CancellingAJobBeforeItsPickupCancelsBothHalves) {
  Courier c({}, GetParam());
  ASSERT_NO_FATAL_FAILURE(c.job("letter", "Office", "Kitchen", "letter"));
  c.fleet().start();
  ASSERT_TRUE(c.executor().cancel_task("letter-drop", "not needed").ok());
  c.settle();
  EXPECT_EQ(c.state("letter-drop"), "cancelled");
  EXPECT_EQ(c.state("letter-pickup"), "cancelled");
  EXPECT_THAT(c.record("letter-pickup").reason, HasSubstr("with the rest of its delivery"));
}

TEST_P(Deliveries, AnObjectOnBoardWhoseDropIsCancelledIsTakenBack) {
  Courier c({}, GetParam());
  ASSERT_NO_FATAL_FAILURE(c.job("letter", "Office", "Kitchen", "letter"));
  c.fleet().start();
  ASSERT_NO_FATAL_FAILURE(c.serve("Office"));
  ASSERT_TRUE(c.executor().cancel_task("letter-drop", "the recipient left").ok());
  c.settle();
  EXPECT_EQ(c.state("letter-drop"), "cancelled");
  ASSERT_TRUE(c.executor().tasks().contains("letter-drop-return"));
  const TaskRecord back = c.record("letter-drop-return");
  EXPECT_EQ(back.task.start_node, "Office");  // its pickup place
  EXPECT_EQ(back.source, "executor");
  EXPECT_EQ(last_event_field(c.store(), "letter-drop", "return planned", &store::Event::code), "return planned");
  EXPECT_EQ(c.executor().on_board().size(), 1u);
  ASSERT_NO_FATAL_FAILURE(c.serve("Office"));
  EXPECT_EQ(c.state("letter-drop-return"), "succeeded");
  EXPECT_TRUE(c.executor().on_board().empty());
}

TEST_P(Deliveries, CapacityKeepsTheLoadOnBoardWithinTheLimit) {
  ExecutorOptions one;
  one.capacity = 1;
  Courier c(one, GetParam());
  ASSERT_NO_FATAL_FAILURE(c.job("letter", "Office", "Kitchen", "letter"));
  ASSERT_NO_FATAL_FAILURE(c.job("book", "Lab", "Kitchen", "book"));
  c.fleet().start();
  const bool letter_first = c.planned("letter-pickup") < c.planned("book-pickup");
  const std::string first = letter_first ? "letter" : "book", second = letter_first ? "book" : "letter";
  EXPECT_LT(c.planned(first + "-drop"), c.planned(second + "-pickup"));
}

}  // namespace
}  // namespace rondo::exec::testing
