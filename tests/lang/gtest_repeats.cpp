// A sentence said again (docs/commands.md, "Saying it again"): lang::settle_ids against the ids an
// executive holds. The same sentence in the same minute is a repeat of what it made; any other
// sentence gets ids of its own, never another's.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <map>

#include "lang/lang_test_support.h"

namespace rondo::lang {
namespace {

// What an executive holds: tasks (and whether each is over) and routines.
struct Book {
  std::map<TaskId, std::pair<Task, bool>> tasks;
  std::map<std::string, Routine> routines;

  Held task(const Task& said) const {
    const auto it = tasks.find(said.id);
    if (it == tasks.end()) return Held::kFree;
    return !it->second.second && it->second.first == said ? Held::kSame : Held::kOther;
  }
  Held routine(const Routine& said) const {
    const auto it = routines.find(said.name);
    if (it == routines.end()) return Held::kFree;
    return same_routine(said, it->second) ? Held::kSame : Held::kOther;
  }
  // Settles `c`, then adds it unless it is a repeat; what settle_ids returned.
  std::vector<std::string> say(Command& c) {
    auto repeated = settle_ids(
        c, [this](const Task& t) { return task(t); }, [this](const Routine& r) { return routine(r); });
    EXPECT_TRUE(repeated.ok()) << repeated.error().message;
    if (!repeated.ok() || !repeated->empty()) return repeated.ok() ? *repeated : std::vector<std::string>{};
    for (const Task& t : c.tasks) EXPECT_TRUE(tasks.emplace(t.id, std::pair{t, false}).second) << t.id;
    for (const Routine& r : c.routines) EXPECT_TRUE(routines.emplace(r.name, r).second) << r.name;
    return {};
  }
};

Command parsed(const std::string& sentence, CommandContext ctx = test::office_context()) {
  auto c = parse_command(sentence, ctx);
  EXPECT_TRUE(c.ok()) << sentence << ": " << c.error().message;
  return c.ok() ? *c : Command{};
}

TEST(Repeats, TheSameSentenceAgainIsARepeatAndAnotherGetsIdsOfItsOwn) {
  Book book;
  Command first = parsed("deliver the red letter from A-111 to A-120 before 15:00");
  EXPECT_TRUE(book.say(first).empty());
  Command again = parsed("deliver the red letter from A-111 to A-120 before 15:00");
  EXPECT_EQ(book.say(again),
            (std::vector<std::string>{"pickup-red-letter@2026-11-23T10:00", "drop-red-letter@2026-11-23T10:00"}));
  // Another delivery of the same object in the same minute: the job and `after` follow the ids.
  Command other = parsed("deliver the red letter from A-110 to A-114");
  EXPECT_TRUE(book.say(other).empty());
  ASSERT_EQ(other.tasks.size(), 2u);
  EXPECT_EQ(other.tasks[0].id, "pickup-red-letter@2026-11-23T10:00~2");
  EXPECT_EQ(other.tasks[1].id, "drop-red-letter@2026-11-23T10:00~2");
  EXPECT_EQ(other.tasks[1].after, std::vector<TaskId>{"pickup-red-letter@2026-11-23T10:00~2"});
  EXPECT_EQ(other.tasks[1].delivery->job, "red-letter@2026-11-23T10:00~2");
  EXPECT_TRUE(validate(other.tasks).ok());
  // A minute later the same sentence is said anew.
  CommandContext later = test::office_context();
  later.now += minutes(1);
  Command next_minute = parsed("deliver the red letter from A-111 to A-120 before 15:00", later);
  EXPECT_TRUE(book.say(next_minute).empty());
  EXPECT_EQ(next_minute.tasks[0].id, "pickup-red-letter@2026-11-23T10:01");
  // A task that is over does not make a repeat: the sentence gets a new id.
  book.tasks.at("pickup-red-letter@2026-11-23T10:00").second = true;
  Command after_done = parsed("deliver the red letter from A-111 to A-120 before 15:00");
  EXPECT_TRUE(book.say(after_done).empty());
  EXPECT_EQ(after_done.tasks[0].id, "pickup-red-letter@2026-11-23T10:00~3");
}

TEST(Repeats, ARoutineSaidAgainOnALaterDayIsTheSameOne) {
  Book book;
  Command first = parsed("check the exits every 2 hours");
  EXPECT_TRUE(book.say(first).empty());
  CommandContext tomorrow = test::office_context();
  tomorrow.now += hours(24);
  Command again = parsed("check the exits every 2 hours", tomorrow);
  EXPECT_EQ(book.say(again), (std::vector<std::string>{"check-exit-west", "check-exit-east"}));
  Command other = parsed("check the west exit every 3 hours", tomorrow);
  EXPECT_TRUE(book.say(other).empty());
  EXPECT_EQ(other.routines.at(0).name, "check-exit-west~2");
  // Said on an earlier day than the one held, it is not covered by it.
  book.routines.at("check-exit-west").first_day = std::chrono::year_month_day{std::chrono::sys_days{
      *book.routines.at("check-exit-west").first_day} + std::chrono::days{3}};
  EXPECT_FALSE(same_routine(parsed("check the west exit every 2 hours").routines.at(0),
                            book.routines.at("check-exit-west")));
}

TEST(Repeats, ACancellationIsNeverARepeatAndTooManySayingsAreAConflict) {
  Book book;
  Command cancel = parsed("cancel the check of A-123");
  EXPECT_TRUE(book.say(cancel).empty());
  Command c = parsed("check A-123");
  auto taken = settle_ids(
      c, [](const Task&) { return Held::kOther; }, [](const Routine&) { return Held::kOther; });
  ASSERT_FALSE(taken.ok());
  EXPECT_EQ(taken.error().code, ErrorCode::kConflict);
  EXPECT_NE(taken.error().message.find("check-a-123@2026-11-23T10:00"), std::string::npos) << taken.error().message;
}

// Whatever sentences are said in one minute, in any order and any number of times: each one said
// before is a repeat of exactly what it made the first time; another is a repeat only of tasks
// the same as its own ("check A-123" after "check A-123 and A-120"), else it is added; and no id
// is ever added twice (the book's tasks stay a valid task set).
RC_GTEST_PROP(Repeats, SaidBeforeIffARepeatAndNoIdIsEverAddedTwice, ()) {
  static const std::vector<std::string> kSentences = {
      "check A-123",
      "check A-123 at 17:00",
      "check A-123 at 18:00",
      "urgent: check A-123",
      "check A-123 and A-120",
      "check A-123 in 10 minutes",
      "check A-123 now",
      "deliver the red letter from A-111 to A-120",
      "deliver the red letter from A-110 to A-114",
      "put the red letter on the meeting table on the desk in A-120",
      "check the exits every 2 hours",
      "check the west exit every 3 hours",
      "patrol A-110 and A-123 every weekday at 9am",
  };
  const auto said = *rc::gen::container<std::vector<std::size_t>>(
      rc::gen::inRange<std::size_t>(0, kSentences.size()));
  Book book;
  std::map<std::size_t, std::vector<std::string>> made;  // sentence -> the ids it made
  for (std::size_t i : said) {
    auto c = parse_command(kSentences[i], test::office_context());
    RC_ASSERT(c.ok());
    auto repeated = settle_ids(
        *c, [&](const Task& t) { return book.task(t); }, [&](const Routine& r) { return book.routine(r); });
    RC_ASSERT(repeated.ok());
    if (made.contains(i)) {
      RC_ASSERT(*repeated == made.at(i));
      continue;
    }
    if (!repeated->empty()) {
      RC_ASSERT(c->routines.empty());
      RC_ASSERT(repeated->size() == c->tasks.size());
      for (std::size_t k = 0; k < c->tasks.size(); ++k) {
        Task held = book.tasks.at((*repeated)[k]).first;
        held.id = c->tasks[k].id;  // the ids, jobs and `after` may carry a "~N"
        held.after = c->tasks[k].after;
        if (held.delivery && c->tasks[k].delivery) held.delivery->job = c->tasks[k].delivery->job;
        RC_ASSERT(held == c->tasks[k]);
      }
      made[i] = *repeated;
      continue;
    }
    std::vector<std::string> ids;
    for (const Task& t : c->tasks) {
      RC_ASSERT(book.tasks.emplace(t.id, std::pair{t, false}).second);
      ids.push_back(t.id);
    }
    for (const Routine& r : c->routines) {
      RC_ASSERT(book.routines.emplace(r.name, r).second);
      ids.push_back(r.name);
    }
    made[i] = ids;
  }
  std::vector<Task> all;
  for (const auto& [id, held] : book.tasks) all.push_back(held.first);
  RC_ASSERT(validate(all).ok());
}

}  // namespace
}  // namespace rondo::lang
