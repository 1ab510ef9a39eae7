#include "rondo/core/task.h"

#include <gtest/gtest.h>

#include <functional>

namespace rondo {
namespace {

Task valid_task() {
  Task t;
  t.id = "t1";
  t.activity = "check the fire extinguisher";
  t.window = TimeWindow{*parse_time("2026-11-23T09:00:00Z"), *parse_time("2026-11-23T10:00:00Z")};
  t.duration = minutes(5);
  t.start_node = "WayPoint1";
  t.actions = {Action{"inspect", {{"object", "extinguisher"}}}};
  return t;
}

TEST(Task, ValidTaskPasses) { EXPECT_TRUE(validate(valid_task()).ok()); }

TEST(Task, EachRuleNamesItsField) {
  struct Case {
    const char* name;
    std::function<void(Task&)> spoil;
    const char* expect;  // start of the message
  };
  const Case cases[] = {
      {"no id", [](Task& t) { t.id.clear(); }, "tasks[0].id: "},
      {"standard without window", [](Task& t) { t.window.reset(); }, "tasks[0].window: a standard task needs"},
      {"on-demand with window", [](Task& t) { t.kind = TaskKind::kOnDemand; }, "tasks[0].window: an on-demand"},
      {"window ends before it starts",
       [](Task& t) { std::swap(t.window->release, t.window->deadline); },
       "tasks[0].window.deadline: deadline 2026-11-23T09:00:00Z is before the release"},
      {"duration longer than window", [](Task& t) { t.duration = hours(2); },
       "tasks[0].duration: duration 2h is longer than the window (1h)"},
      {"negative duration", [](Task& t) { t.duration = seconds(-1); }, "tasks[0].duration: must not be negative"},
      {"end without start", [](Task& t) { t.start_node.clear(); t.end_node = "B"; }, "tasks[0].end_node: "},
      {"unnamed action", [](Task& t) { t.actions.push_back(Action{}); }, "tasks[0].actions[1].name: "},
      {"delivery without job", [](Task& t) { t.delivery = Delivery{"", DeliveryRole::kPickup, "book", "book", 1}; },
       "tasks[0].delivery.job: "},
      {"delivery load zero", [](Task& t) { t.delivery = Delivery{"j", DeliveryRole::kPickup, "book", "book", 0}; },
       "tasks[0].delivery.load: "},
      {"after itself", [](Task& t) { t.after = {"t1"}; }, "tasks[0].after[0]: a task cannot come after itself"},
      {"after twice", [](Task& t) { t.after = {"x", "x"}; }, "tasks[0].after[1]: 'x' is listed twice"},
  };
  for (const auto& c : cases) {
    Task t = valid_task();
    c.spoil(t);
    auto s = validate(t, "tasks[0]");
    ASSERT_FALSE(s.ok()) << c.name;
    EXPECT_EQ(s.error().code, ErrorCode::kInvalidInput);
    EXPECT_EQ(s.error().message.rfind(c.expect, 0), 0u) << c.name << ": " << s.error().message;
  }
}

TEST(Task, SetRules) {
  auto with_id = [](std::string id) {
    Task t = valid_task();
    t.id = std::move(id);
    return t;
  };
  struct Case {
    const char* name;
    std::function<std::vector<Task>()> make;
    const char* expect;
  };
  const Case cases[] = {
      {"duplicate id", [&] { return std::vector<Task>{with_id("a"), with_id("a")}; }, "tasks[1].id: duplicate task id 'a'"},
      {"after unknown",
       [&] {
         auto t = with_id("a");
         t.after = {"ghost"};
         return std::vector<Task>{t};
       },
       "tasks[0].after[0]: no task 'ghost'"},
      {"cycle",
       [&] {
         auto a = with_id("a");
         auto b = with_id("b");
         a.after = {"b"};
         b.after = {"a"};
         return std::vector<Task>{a, b};
       },
       "precedence cycle"},
      {"job without drop",
       [&] {
         auto a = with_id("a");
         a.delivery = Delivery{"j", DeliveryRole::kPickup, "book", "book", 1};
         return std::vector<Task>{a};
       },
       "job 'j' has no drop task"},
      {"two pickups",
       [&] {
         auto a = with_id("a");
         auto b = with_id("b");
         a.delivery = b.delivery = Delivery{"j", DeliveryRole::kPickup, "book", "book", 1};
         return std::vector<Task>{a, b};
       },
       "already has a pickup task ('a')"},
      {"drop of another object",
       [&] {
         auto a = with_id("a");
         auto b = with_id("b");
         a.delivery = Delivery{"j", DeliveryRole::kPickup, "book", "book", 1};
         b.delivery = Delivery{"j", DeliveryRole::kDrop, "mug", "mug", 1};
         return std::vector<Task>{a, b};
       },
       "the drop names another object"},
  };
  for (const auto& c : cases) {
    auto s = validate(c.make());
    ASSERT_FALSE(s.ok()) << c.name;
    EXPECT_NE(s.error().message.find(c.expect), std::string::npos) << c.name << ": " << s.error().message;
  }
  EXPECT_TRUE(validate(std::vector<Task>{with_id("a"), with_id("b")}).ok());
}

TEST(Task, StatesAndKindsRoundTripAsText) {
  for (auto s : {TaskState::kQueued, TaskState::kWaiting, TaskState::kNavigating, TaskState::kActing,
                 TaskState::kSucceeded, TaskState::kFailed, TaskState::kCancelled, TaskState::kPreempted,
                 TaskState::kDropped}) {
    EXPECT_EQ(*parse_task_state(to_string(s)), s);
  }
  EXPECT_TRUE(is_final(TaskState::kDropped));
  EXPECT_FALSE(is_final(TaskState::kWaiting));
  EXPECT_EQ(*parse_task_kind("on-demand"), TaskKind::kOnDemand);
  EXPECT_FALSE(parse_task_kind("urgent").ok());
  EXPECT_FALSE(parse_delivery_role("carry").ok());
}

}  // namespace
}  // namespace rondo
