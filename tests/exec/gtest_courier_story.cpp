// The courier's story (MISSION.md §5, issue 16's acceptance) as a scenario test on the office
// example (examples/office: its map and places), asserting on the event log: the paper's two
// commands given as sentences; the first schedule interleaves the two pickups before the two
// drops; A-120's door is seen closed after the letter is picked up, when the robot reaches A-120:
// it reschedules at once, delivers nothing to A-120 and keeps the letter as an opportunity; the
// door is seen open again while it heads to A-114: it interrupts, delivers the letter, then the
// book. Variants: the door never reopens; two red letters; a kill in the middle.
//
// The world is scripted (the ScriptedRobot): every edge takes 20 s, every load and unload is
// confirmed at once, and the door sequence is the test's.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "rondo/exec/executor.h"
#include "rondo/lang/command.h"
#include "rondo/lang/places.h"
#include "rondo/map/map_loader.h"
#include "rondo/store/observations.h"
#include "scripted_executor.h"

namespace rondo::exec::testing {
namespace {

using ::testing::HasSubstr;

// The paper's two commands, verbatim, except the deadline of the letter: with no deadline the
// book's desk (on the way) comes first and the story would start at A-114.
constexpr const char* kLetter =
    "put the red letter on the meeting table in room A-111 on the desk in room A-120 before 08:08";
constexpr const char* kBook =
    "deliver the green book from the librarian's desk in room A-110 to the desk in room A-114";

class Story : public ScriptedExecutor {
 public:
  Story()
      : ScriptedExecutor({}, map::load_map("examples/office/map.yaml").value(), {}, "ChargingPoint"),
        places_(lang::Places::load("examples/office/places.yaml", map_).value()) {}

  // The tasks a sentence means, added as a person's request; returns their ids (pickup, drop).
  std::vector<TaskId> say(const std::string& sentence) {
    const lang::CommandContext ctx{.places = &places_, .zone = zone_, .now = clock_.now()};
    auto command = lang::parse_command(sentence, ctx);
    EXPECT_TRUE(command.ok()) << (command.ok() ? "" : command.error().message);
    if (!command.ok()) return {};
    std::vector<TaskId> ids;
    for (const Task& t : command->tasks) ids.push_back(t.id);
    EXPECT_TRUE(fleet().add_tasks(command->tasks, "words").ok());
    return ids;
  }
  Time planned(const TaskId& id) const { return executor_->tasks().at(id).planned_start.value(); }
  std::vector<store::Event> all_events() const { return store::read_events(store_).value(); }
  std::vector<store::Event> events_of(const TaskId& id) const { return store::read_events_of(store_, id).value(); }
  // The sequence number of the task's first event named `event` (0 when there is none).
  std::int64_t seq_of(const TaskId& id, const std::string& event) const {
    for (const store::Event& e : events_of(id))
      if (e.event == event) return e.seq;
    return 0;
  }
  std::string node() const { return map_.node(robot_.location()).name; }
  std::string heading_to() const {
    return robot_.edge() ? map_.node(map_.to_index(*robot_.edge())).name : std::string("nowhere");
  }
  // Answers edges with success after 20 s until the robot stands at `target`.
  void drive_to(const std::string& target) {
    for (int guard = 0; node() != target && guard < 60; ++guard) {
      settle();
      ASSERT_TRUE(robot_.driving()) << "no edge asked for on the way to " << target << " (at " << node() << ")";
      step();
    }
    settle();
  }
  void step() {
    clock_.run_until(clock_.now() + seconds(5));
    robot_.finish_edge(EdgeOutcome::kSucceeded, seconds(5));
    visited_.push_back(node());
    settle();
  }
  // Drives to `target` and confirms its one action (a load or an unload).
  void serve(const std::string& target) {
    ASSERT_NO_FATAL_FAILURE(drive_to(target));
    ASSERT_TRUE(robot_.acting()) << "no action at " << target;
    clock_.run_until(clock_.now() + seconds(10));
    robot_.finish_action(ActionOutcome::kSucceeded);
    settle();
  }
  // The robot stood at `node` (the node inside a room's door: it went in).
  bool entered(const std::string& node) const {
    return std::find(visited_.begin(), visited_.end(), node) != visited_.end();
  }

 protected:
  lang::Places places_;
  std::vector<std::string> visited_;
};

// Both commands at 08:00, started, both pickups done (in the planned order); the robot then heads
// for A-120 with the letter and stands in front of its door.
struct Started {
  TaskId letter_pickup, letter_drop, book_pickup, book_drop;
};

Started pick_up_both_and_reach_a120(Story& s) {
  Started ids;
  const std::vector<TaskId> letter = s.say(kLetter);
  const std::vector<TaskId> book = s.say(kBook);
  EXPECT_EQ(letter.size(), 2u);
  EXPECT_EQ(book.size(), 2u);
  if (letter.size() != 2 || book.size() != 2) return ids;
  ids = {letter[0], letter[1], book[0], book[1]};
  s.fleet().start();
  s.settle();
  // The first schedule interleaves: both pickups before both drops, the letter's drop first.
  EXPECT_LT(std::max(s.planned(ids.letter_pickup), s.planned(ids.book_pickup)),
            std::min(s.planned(ids.letter_drop), s.planned(ids.book_drop)));
  EXPECT_LT(s.planned(ids.letter_drop), s.planned(ids.book_drop));
  // It records what it assumes: the door of A-120 open for the letter's drop.
  const auto& a = s.executor().assumptions();
  EXPECT_TRUE(std::any_of(a.begin(), a.end(), [&](const Assumption& x) {
    return x.kind == Assumption::Kind::kDoorOpen && x.what == "A-120-door" && x.task == ids.letter_drop;
  }));
  const bool book_first = s.planned(ids.book_pickup) < s.planned(ids.letter_pickup);
  s.serve(book_first ? "A-110-Desk" : "A-111-Table");
  s.serve(book_first ? "A-111-Table" : "A-110-Desk");
  EXPECT_EQ(s.state(ids.letter_pickup), "succeeded");
  EXPECT_EQ(s.state(ids.book_pickup), "succeeded");
  s.drive_to("Hall-A-120");
  EXPECT_EQ(s.heading_to(), "A-120") << "the letter's drop goes through A-120's door";
  return ids;
}

TEST(CourierStory, TheDoorClosesTheLetterWaitsAndIsDeliveredWhenTheDoorIsSeenOpen) {
  Story s;
  const Started ids = pick_up_both_and_reach_a120(s);
  ASSERT_FALSE(ids.letter_drop.empty());
  ASSERT_FALSE(HasFailure());
  // A-120's door is seen closed from the hallway: rescheduled at once, while the robot moves.
  s.robot().observe("door_open", "A-120-door", 0);
  s.settle();
  EXPECT_EQ(s.code_of(ids.letter_drop, "blocked"), "assumption broken");
  EXPECT_THAT(s.reason_of(ids.letter_drop, "blocked"), HasSubstr("'door open A-120-door'"));
  EXPECT_THAT(s.reason_of(ids.letter_drop, "blocked"), HasSubstr("A-120-door seen closed from Hall-A-120"));
  EXPECT_EQ(s.code_of(ids.letter_drop, "queued"), "assumption broken");
  EXPECT_EQ(s.state(ids.letter_drop), "queued");
  const std::vector<store::Event> all = s.all_events();
  const auto resched = std::find_if(all.begin(), all.end(), [](const store::Event& e) {
    return e.subject == store::Subject::kSchedule && e.event == "rescheduled";
  });
  ASSERT_NE(resched, all.end());
  EXPECT_EQ(resched->code, "assumption broken");
  EXPECT_THAT(resched->reason, HasSubstr("A-120-door seen closed"));
  EXPECT_THAT(resched->reason, HasSubstr("the plan was " + ids.letter_drop + ", " + ids.book_drop));
  EXPECT_THAT(resched->reason, HasSubstr("it is now " + ids.book_drop));
  EXPECT_EQ(s.executor().on_board().size(), 2u);  // the letter stays on board
  // Off to A-114 with the book; one edge on, A-120's door is seen open.
  s.settle();
  EXPECT_EQ(s.executor().current_task(), ids.book_drop);
  EXPECT_EQ(s.heading_to(), "Hall-A-117");
  s.step();
  EXPECT_EQ(s.node(), "Hall-A-117");
  s.robot().observe("door_open", "A-120-door", 1);
  s.settle();
  EXPECT_EQ(s.code_of(ids.letter_drop, "opportunity"), "opportunity taken");
  EXPECT_THAT(s.reason_of(ids.letter_drop, "opportunity"), HasSubstr("interrupts " + ids.book_drop));
  EXPECT_EQ(s.code_of(ids.book_drop, "queued"), "opportunity taken");
  EXPECT_FALSE(s.entered("A-120")) << "nothing went to A-120 while its door was closed";
  ASSERT_NO_FATAL_FAILURE(s.serve("A-120-Desk"));
  EXPECT_EQ(s.state(ids.letter_drop), "succeeded");
  ASSERT_NO_FATAL_FAILURE(s.serve("A-114-Desk"));
  EXPECT_EQ(s.state(ids.book_drop), "succeeded");
  EXPECT_LT(s.seq_of(ids.letter_drop, "succeeded"), s.seq_of(ids.book_drop, "succeeded"));
  EXPECT_TRUE(s.executor().on_board().empty());
  EXPECT_EQ(s.executor().assumption_stats().broken, 1);
  EXPECT_EQ(s.executor().assumption_stats().reschedules, 1);
  EXPECT_EQ(s.executor().assumption_stats().opportunities_taken, 1);
}

// The building's sensor (Executor::observe, as POST /api/v1/observations calls it) sees the door
// instead of the robot: the same break, reschedule and opportunity, the sensor named in the log,
// and the observations stored without a robot.
TEST(CourierStory, TheBuildingsSensorSeesTheDoorAsTheRobotWould) {
  Story s;
  const Started ids = pick_up_both_and_reach_a120(s);
  ASSERT_FALSE(ids.letter_drop.empty());
  ASSERT_FALSE(HasFailure());
  const auto building = [&s](double value) {
    s.executor().observe({.what = std::string(Observation::kDoorOpen), .where = "A-120-door",
                          .when = s.clock().now(), .value = value, .source = "door-sensor-7"});
    s.settle();
  };
  building(0);
  EXPECT_EQ(s.code_of(ids.letter_drop, "blocked"), "assumption broken");
  EXPECT_THAT(s.reason_of(ids.letter_drop, "blocked"), HasSubstr("A-120-door seen closed from door-sensor-7"));
  EXPECT_EQ(s.state(ids.letter_drop), "queued");
  EXPECT_EQ(s.executor().assumption_stats().reschedules, 1);
  s.step();
  building(1);
  EXPECT_EQ(s.code_of(ids.letter_drop, "opportunity"), "opportunity taken");
  EXPECT_THAT(s.reason_of(ids.letter_drop, "opportunity"), HasSubstr("seen open from door-sensor-7"));
  ASSERT_NO_FATAL_FAILURE(s.serve("A-120-Desk"));
  EXPECT_EQ(s.state(ids.letter_drop), "succeeded");
  const auto seen = store::find_observations(s.store(), {.what = "door_open", .where = "A-120-door"}).value();
  ASSERT_EQ(seen.size(), 2u);
  for (const store::Observation& o : seen) {
    EXPECT_EQ(o.robot, "") << "the building's, not the robot's";
    EXPECT_EQ(o.text, "from door-sensor-7");
  }
}

TEST(CourierStory, TheDoorNeverReopensTheLetterFailsAtItsDeadlineAndTheBookIsDelivered) {
  Story s;
  const Started ids = pick_up_both_and_reach_a120(s);
  ASSERT_FALSE(ids.letter_drop.empty());
  ASSERT_FALSE(HasFailure());
  s.robot().observe("door_open", "A-120-door", 0);
  s.settle();
  EXPECT_FALSE(s.entered("A-120"));
  ASSERT_NO_FATAL_FAILURE(s.serve("A-114-Desk"));
  EXPECT_EQ(s.state(ids.book_drop), "succeeded");
  EXPECT_EQ(s.state(ids.letter_drop), "queued");  // still waiting, its deadline allows
  // The robot goes home; the door is never seen open; the letter's deadline passes.
  s.drive_to("ChargingPoint");
  s.run_until("08:10");
  EXPECT_EQ(s.state(ids.letter_drop), "failed");
  EXPECT_EQ(s.code_of(ids.letter_drop, "failed"), "assumption broken");
  EXPECT_THAT(s.reason_of(ids.letter_drop, "failed"), HasSubstr("A-120-door seen closed from Hall-A-120"));
  EXPECT_THAT(s.reason_of(ids.letter_drop, "failed"), HasSubstr("not seen open since"));
  EXPECT_FALSE(s.entered("A-120"));
  // The letter is on board: a task takes it back to the meeting table.
  EXPECT_EQ(s.code_of(ids.letter_drop, "return planned"), "return planned");
  EXPECT_EQ(s.executor().assumption_stats().failed_blocked, 1);
}

TEST(CourierStory, ADoorSeenClosedFromInsideWhileActingBreaksNothing) {
  Story s;
  const std::vector<TaskId> book = s.say(kBook);
  ASSERT_EQ(book.size(), 2u);
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("A-110-Desk"));
  ASSERT_TRUE(s.robot().acting());
  s.robot().observe("door_open", "A-110-door", 0);
  s.settle();
  EXPECT_EQ(s.code_of(book[0], "blocked"), "");
  EXPECT_TRUE(s.robot().acting());
  EXPECT_EQ(s.executor().assumption_stats().broken, 0);
  EXPECT_EQ(s.executor().assumption_stats().door_observations, 1);
}

TEST(CourierStory, AnOnDemandTaskIsNotBlockedByItsDoor) {
  Story s;
  s.fleet().start();
  s.settle();
  Task come;
  come.id = "come";
  come.activity = "come to A-120";
  come.kind = TaskKind::kOnDemand;
  come.duration = minutes(2);
  come.start_node = "A-120";
  come.actions = {Action{.name = "visit", .args = {}}};
  ASSERT_TRUE(s.fleet().add_task(come, "test").ok());
  s.settle();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Hall-A-117"));
  s.robot().observe("door_open", "A-120-door", 0);
  s.settle();
  EXPECT_EQ(s.code_of("come", "blocked"), "");
  EXPECT_EQ(s.executor().current_task(), "come");
  EXPECT_TRUE(s.robot().driving());
}

// A job as the requests make it: the halves linked by their job only (no `after`). Its pickup's
// door seen closed blocks the drop too (a drop is never planned without its pickup), and the door
// seen open brings both back: the pickup as the opportunity, then the drop.
TEST(CourierStory, BothHalvesOfAJobWaitForThePickupsDoor) {
  Story s;
  std::vector<Task> job;
  for (const auto& [role, node] : {std::pair{DeliveryRole::kPickup, "A-120-Desk"}, {DeliveryRole::kDrop, "A-110-Desk"}}) {
    Task t;
    t.id = role == DeliveryRole::kPickup ? "parcel-pickup" : "parcel-drop";
    t.activity = t.id;
    t.window = TimeWindow{s.at("08:00"), s.at("11:00")};
    t.duration = minutes(1);
    t.start_node = node;
    t.actions = {Action{.name = role == DeliveryRole::kPickup ? "load" : "unload", .args = {}}};
    t.delivery = Delivery{.job = "parcel", .role = role, .object = "parcel", .appearance = "parcel", .load = 1};
    job.push_back(t);
  }
  ASSERT_TRUE(s.fleet().add_tasks(job, "requests").ok());
  s.fleet().start();
  ASSERT_NO_FATAL_FAILURE(s.drive_to("Hall-A-120"));
  s.robot().observe("door_open", "A-120-door", 0);
  s.settle();
  EXPECT_EQ(s.code_of("parcel-pickup", "blocked"), "assumption broken");
  EXPECT_EQ(s.code_of("parcel-drop", "blocked"), "assumption broken");
  for (const store::Event& e : s.all_events()) EXPECT_NE(e.event, "not rescheduled") << e.reason;
  EXPECT_NE(s.executor().current_task(), std::optional<TaskId>("parcel-drop"));
  s.robot().observe("door_open", "A-120-door", 1);
  s.settle();
  EXPECT_EQ(s.code_of("parcel-pickup", "opportunity"), "opportunity taken");
  ASSERT_NO_FATAL_FAILURE(s.serve("A-120-Desk"));
  ASSERT_NO_FATAL_FAILURE(s.serve("A-110-Desk"));
  EXPECT_EQ(s.state("parcel-pickup"), "succeeded");
  EXPECT_EQ(s.state("parcel-drop"), "succeeded");
}

TEST(CourierStory, TwoRedLettersAreNeverOnBoardTogetherAndTheScheduleSaysWhy) {
  Story s;
  const std::vector<TaskId> first = s.say(kLetter);
  s.run_until("08:01");
  const std::vector<TaskId> second =
      s.say("deliver the red letter from the librarian's desk in room A-110 to the desk in room A-114");
  ASSERT_EQ(first.size(), 2u);
  ASSERT_EQ(second.size(), 2u);
  s.fleet().start();
  s.settle();
  const bool first_first = s.planned(first[0]) < s.planned(second[0]);
  const std::vector<TaskId>& a = first_first ? first : second;
  const std::vector<TaskId>& b = first_first ? second : first;
  EXPECT_LT(s.planned(a[1]), s.planned(b[0])) << "the first letter is dropped before the second is picked up";
  const std::vector<store::Event> all = s.all_events();
  const auto why = std::find_if(all.begin(), all.end(), [](const store::Event& e) {
    return e.subject == store::Subject::kSchedule && e.event == "look-alike";
  });
  ASSERT_NE(why, all.end());
  EXPECT_THAT(why->reason, HasSubstr("'red letter'"));
  EXPECT_THAT(why->reason, HasSubstr("never on board together"));
  // And so it goes: at no moment are both on board.
  std::size_t most = 0;
  const auto serve_next = [&] {
    const std::optional<TaskId> now = s.executor().current_task();
    ASSERT_TRUE(now.has_value());
    s.serve(s.executor().tasks().at(*now).task.start_node);
    most = std::max(most, s.executor().on_board().size());
  };
  for (int i = 0; i < 4; ++i) ASSERT_NO_FATAL_FAILURE(serve_next());
  EXPECT_EQ(most, 1u);
  for (const TaskId& id : {a[0], a[1], b[0], b[1]}) EXPECT_EQ(s.state(id), "succeeded") << id;
}

TEST(CourierStory, AfterAKillTheLetterOnBoardIsNotPickedUpAgain) {
  Story s;
  const std::vector<TaskId> letter = s.say(kLetter);
  const std::vector<TaskId> book = s.say(kBook);
  ASSERT_EQ(letter.size(), 2u);
  s.fleet().start();
  s.settle();
  // Serve the pickups in order until the letter is on board, then kill the executive.
  while (s.state(letter[0]) != "succeeded") {
    const std::optional<TaskId> now = s.executor().current_task();
    ASSERT_TRUE(now.has_value());
    ASSERT_NO_FATAL_FAILURE(s.serve(s.executor().tasks().at(*now).task.start_node));
  }
  const std::size_t calls_before = s.robot().calls.size();
  ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
  s.settle();
  ASSERT_EQ(s.state(letter[0]), "succeeded");
  const std::vector<OnBoard> on = s.executor().on_board();
  ASSERT_TRUE(std::any_of(on.begin(), on.end(), [&](const OnBoard& o) { return o.picked_up_by == letter[0]; }));
  // The rest runs to the end; the meeting table is never visited again.
  for (int i = 0; i < 6 && s.executor().current_task(); ++i) {
    const TaskId now = *s.executor().current_task();
    EXPECT_NE(now, letter[0]);
    ASSERT_NO_FATAL_FAILURE(s.serve(s.executor().tasks().at(now).task.start_node));
  }
  for (const TaskId& id : {letter[1], book[0], book[1]}) EXPECT_EQ(s.state(id), "succeeded") << id;
  const std::vector<std::string> after(s.robot().calls.begin() + static_cast<std::ptrdiff_t>(calls_before),
                                       s.robot().calls.end());
  EXPECT_FALSE(std::any_of(after.begin(), after.end(),
                           [](const std::string& c) { return c.starts_with("drive A-111_A-111-Table"); }));
}

// A kill while the letter waits for A-120's door: after the restore it still waits for the door
// (stored with its progress), is not driven to A-120, and is taken when the door is seen open.
TEST(CourierStory, AfterAKillTheLetterStillWaitsForItsDoor) {
  Story s;
  const Started ids = pick_up_both_and_reach_a120(s);
  ASSERT_FALSE(ids.letter_drop.empty());
  ASSERT_FALSE(HasFailure());
  s.robot().observe("door_open", "A-120-door", 0);
  s.settle();
  ASSERT_EQ(s.executor().current_task(), ids.book_drop);
  ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
  s.settle();
  const TaskRecord& letter = s.executor().tasks().at(ids.letter_drop);
  EXPECT_EQ(s.state(ids.letter_drop), "queued");
  ASSERT_TRUE(letter.door_wait.has_value());
  EXPECT_EQ(letter.door_wait->door, "A-120-door");
  EXPECT_EQ(letter.door_wait->seen_at, "Hall-A-120");
  const Executor::Activity now = s.executor().activity();
  EXPECT_EQ(now.current, ids.book_drop);
  EXPECT_EQ(std::count(now.planned.begin(), now.planned.end(), ids.letter_drop), 0) << "kept out of the schedule";
  s.step();
  EXPECT_EQ(s.node(), "Hall-A-117");
  s.robot().observe("door_open", "A-120-door", 1);
  s.settle();
  EXPECT_EQ(s.code_of(ids.letter_drop, "opportunity"), "opportunity taken");
  EXPECT_FALSE(s.entered("A-120")) << "nothing went to A-120 while its door was closed";
  ASSERT_NO_FATAL_FAILURE(s.serve("A-120-Desk"));
  EXPECT_EQ(s.state(ids.letter_drop), "succeeded");
  EXPECT_FALSE(s.executor().tasks().at(ids.letter_drop).door_wait.has_value());
  ASSERT_NO_FATAL_FAILURE(s.serve("A-114-Desk"));
  EXPECT_EQ(s.state(ids.book_drop), "succeeded");
}

// Still blocked after the restart and never seen open: it fails at its latest start for its door.
TEST(CourierStory, AfterAKillABlockedLetterFailsForItsDoorAtItsDeadline) {
  Story s;
  const Started ids = pick_up_both_and_reach_a120(s);
  ASSERT_FALSE(ids.letter_drop.empty());
  ASSERT_FALSE(HasFailure());
  s.robot().observe("door_open", "A-120-door", 0);
  s.settle();
  ASSERT_NO_FATAL_FAILURE(s.kill_and_restart());
  ASSERT_NO_FATAL_FAILURE(s.serve("A-114-Desk"));
  s.drive_to("ChargingPoint");
  s.run_until("08:10");
  EXPECT_EQ(s.state(ids.letter_drop), "failed");
  EXPECT_EQ(s.code_of(ids.letter_drop, "failed"), "assumption broken");
  EXPECT_THAT(s.reason_of(ids.letter_drop, "failed"), HasSubstr("A-120-door seen closed from Hall-A-120"));
  EXPECT_FALSE(s.entered("A-120"));
}

}  // namespace
}  // namespace rondo::exec::testing
