// The command language, sentence by sentence (docs/commands.md): each accepted sentence with the
// tasks, routines or cancellation it must mean, each rejected one with the words its error must
// contain. Context: examples/office, Monday 2026-11-23 10:00 in London (GMT: local = UTC).
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "lang/lang_test_support.h"
#include "rondo/core/task_codec.h"
#include "rondo/ltl/formula.h"
#include "rondo/ltl/parser.h"

namespace rondo::lang {
namespace {

// A task as "<id> <[dd hh:mm,dd hh:mm]|now> <duration> p<priority> @<node> <actions>[ <role>:<job>
// '<object>'][ after:<id>]"; times local (London = UTC in November).
std::string describe(const Task& t) {
  auto when = [](Time x) {
    const auto z = *TimeZone::named("Europe/London");
    const std::string s = z.format_local(x);  // 2026-11-23T10:00:00+00:00
    return s.substr(8, 2) + " " + s.substr(11, 5);
  };
  std::string out = t.id + " ";
  out += t.window ? "[" + when(t.window->release) + "," + when(t.window->deadline) + "]" : "now";
  out += fmt::format(" {} p{} @{}", format_duration(t.duration), t.priority, t.start_node);
  for (const auto& a : t.actions) out += " " + a.name;
  if (t.delivery) {
    out += fmt::format(" {}:{} '{}'", to_string(t.delivery->role), t.delivery->job, t.delivery->object);
  }
  for (const auto& a : t.after) out += " after:" + a;
  return out;
}

std::string day_names(const std::vector<std::chrono::weekday>& days) {
  if (days.empty()) return "daily";
  static const char* kNames[] = {"sun", "mon", "tue", "wed", "thu", "fri", "sat"};
  std::vector<std::string> names;
  for (auto d : days) names.emplace_back(kNames[d.c_encoding()]);
  return fmt::format("{}", fmt::join(names, ","));
}

// "routine <name> <hh:mm>-<hh:mm>[ every <d>] <days> <duration> p<priority> @<node> <actions>".
std::string describe(const Routine& r) {
  std::string out =
      fmt::format("routine {} {}-{}", r.name, format_time_of_day(r.window_start), format_time_of_day(r.window_end));
  if (r.every) out += " every " + format_duration(*r.every);
  out += fmt::format(" {} {} p{} @{}", day_names(r.days), format_duration(r.task.duration), r.task.priority,
                     r.task.start_node);
  for (const auto& a : r.task.actions) out += " " + a.name;
  return out;
}

std::string describe(const Command& c) {
  std::vector<std::string> parts;
  for (const auto& t : c.tasks) parts.push_back(describe(t));
  for (const auto& r : c.routines) parts.push_back(describe(r));
  if (c.cancel) {
    const auto& x = *c.cancel;
    if (x.what == Cancellation::What::kDelivery) parts.push_back("cancel delivery '" + x.object + "'");
    if (x.what == Cancellation::What::kActivity) {
      parts.push_back(fmt::format("cancel {} @{}", x.activity, fmt::join(x.nodes, ",")));
    }
    if (x.what == Cancellation::What::kTask) parts.push_back("cancel task " + x.id);
  }
  return fmt::format("{}", fmt::join(parts, "; "));
}

struct Case {
  const char* sentence;
  const char* expected;  // describe() of the command, or the error text it must contain
  bool accepted;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << '"' << c.sentence << '"';
}

constexpr const char* kT = "@2026-11-23T10:00";

std::string with_tag(std::string text) {
  for (std::size_t at = text.find("@T"); at != std::string::npos; at = text.find("@T", at)) {
    text.replace(at, 2, kT);
  }
  return text;
}

// "@T" in an expectation stands for the id tag of the command's time, "@2026-11-23T10:00".
const Case kAccepted[] = {
    // The paper's two commands, verbatim.
    {"put the red letter on the meeting table in room A-111 on the desk in room A-120",
     "pickup-red-letter@T [23 10:00,24 00:00] 1m p0 @A-111-Table load pickup:red-letter@T 'red letter'; "
     "drop-red-letter@T [23 10:00,24 00:00] 1m p0 @A-120-Desk unload drop:red-letter@T 'red letter' "
     "after:pickup-red-letter@T",
     true},
    {"deliver the green book from the librarian's desk in room A-110 to the desk in room A-114",
     "pickup-green-book@T [23 10:00,24 00:00] 1m p0 @A-110-Desk load pickup:green-book@T 'green book'; "
     "drop-green-book@T [23 10:00,24 00:00] 1m p0 @A-114-Desk unload drop:green-book@T 'green book' "
     "after:pickup-green-book@T",
     true},
    // Deadlines and windows.
    {"deliver the red letter from A-111 to A-120 before 15:00",
     "pickup-red-letter@T [23 10:00,23 15:00] 1m p0 @A-111 load pickup:red-letter@T 'red letter'; "
     "drop-red-letter@T [23 10:00,23 15:00] 1m p0 @A-120 unload drop:red-letter@T 'red letter' "
     "after:pickup-red-letter@T",
     true},
    {"check office A-123 between 20:00 and 20:15", "check-a-123@T [23 20:00,23 20:15] 2m p0 @A-123 check", true},
    // Routines.
    {"check the emergency exits every 2 hours",
     "routine check-exit-west 00:00-24:00 every 2h daily 2m p0 @Exit-West check; "
     "routine check-exit-east 00:00-24:00 every 2h daily 2m p0 @Exit-East check",
     true},
    {"patrol the hallway every weekday at 09:00",
     "routine patrol-hall-west 09:00-09:30 mon,tue,wed,thu,fri 2m p0 @Hall-West patrol; "
     "routine patrol-hall-a-110 09:00-09:30 mon,tue,wed,thu,fri 2m p0 @Hall-A-110 patrol; "
     "routine patrol-hall-a-111 09:00-09:30 mon,tue,wed,thu,fri 2m p0 @Hall-A-111 patrol; "
     "routine patrol-hall-a-114 09:00-09:30 mon,tue,wed,thu,fri 2m p0 @Hall-A-114 patrol; "
     "routine patrol-hall-a-117 09:00-09:30 mon,tue,wed,thu,fri 2m p0 @Hall-A-117 patrol; "
     "routine patrol-hall-a-120 09:00-09:30 mon,tue,wed,thu,fri 2m p0 @Hall-A-120 patrol; "
     "routine patrol-hall-a-123 09:00-09:30 mon,tue,wed,thu,fri 2m p0 @Hall-A-123 patrol; "
     "routine patrol-hall-east 09:00-09:30 mon,tue,wed,thu,fri 2m p0 @Hall-East patrol",
     true},
    // Priorities and on-demand.
    {"urgent: come to A-110 now", "visit-a-110@T now 5m p10 @A-110 visit", true},
    // Cancellation.
    {"cancel the delivery of the red letter", "cancel delivery 'red letter'", true},
    // Case, typographic apostrophes, people.
    {"Deliver the Green Book from the Librarian\u2019s Desk in Room A-110 to Michael",
     "pickup-green-book@T [23 10:00,24 00:00] 1m p0 @A-110-Desk load pickup:green-book@T 'green book'; "
     "drop-green-book@T [23 10:00,24 00:00] 1m p0 @A-114-Desk unload drop:green-book@T 'green book' "
     "after:pickup-green-book@T",
     true},
    {"bring the parcel from the kitchen to Anna's desk",
     "pickup-parcel@T [23 10:00,24 00:00] 1m p0 @A-117 load pickup:parcel@T 'parcel'; "
     "drop-parcel@T [23 10:00,24 00:00] 1m p0 @A-120-Desk unload drop:parcel@T 'parcel' after:pickup-parcel@T",
     true},
    {"take the keys from the charger to the east exit tomorrow",
     "pickup-keys@T [24 00:00,25 00:00] 1m p0 @ChargingPoint load pickup:keys@T 'keys'; "
     "drop-keys@T [24 00:00,25 00:00] 1m p0 @Exit-East unload drop:keys@T 'keys' after:pickup-keys@T",
     true},
    {"carry the files from A-123 to A-111 after 14:00",
     "pickup-files@T [23 14:00,24 00:00] 1m p0 @A-123 load pickup:files@T 'files'; "
     "drop-files@T [23 14:00,24 00:00] 1m p0 @A-111 unload drop:files@T 'files' after:pickup-files@T",
     true},
    {"deliver the red letter from A-111 to A-120 by 3pm",
     "pickup-red-letter@T [23 10:00,23 15:00] 1m p0 @A-111 load pickup:red-letter@T 'red letter'; "
     "drop-red-letter@T [23 10:00,23 15:00] 1m p0 @A-120 unload drop:red-letter@T 'red letter' "
     "after:pickup-red-letter@T",
     true},
    {"deliver the red letter from A-111 to A-120 now",
     "pickup-red-letter@T now 1m p0 @A-111 load pickup:red-letter@T 'red letter'; "
     "drop-red-letter@T now 1m p0 @A-120 unload drop:red-letter@T 'red letter' after:pickup-red-letter@T",
     true},
    {"put the blue folder on the desk in A-123 onto the table in A-111",
     "pickup-blue-folder@T [23 10:00,24 00:00] 1m p0 @A-123-Desk load pickup:blue-folder@T 'blue folder'; "
     "drop-blue-folder@T [23 10:00,24 00:00] 1m p0 @A-111-Table unload drop:blue-folder@T 'blue folder' "
     "after:pickup-blue-folder@T",
     true},
    {"check A-123 at 17:00", "check-a-123@T [23 17:00,23 17:30] 2m p0 @A-123 check", true},
    {"inspect the meeting table in A-111 for 10 minutes",
     "check-a-111-table@T [23 10:00,24 00:00] 10m p0 @A-111-Table check", true},
    {"visit Tom on friday between 09:00 and 10:00", "visit-a-123-desk@T [27 09:00,27 10:00] 5m p0 @A-123-Desk visit",
     true},
    {"go to the library now", "visit-a-110@T now 5m p0 @A-110 visit", true},
    {"important: check the kitchen before noon", "check-a-117@T [23 10:00,23 12:00] 2m p5 @A-117 check", true},
    {"check the east exit with priority 3", "check-exit-east@T [23 10:00,24 00:00] 2m p3 @Exit-East check", true},
    {"please check Michael's office", "check-a-114-desk@T [23 10:00,24 00:00] 2m p0 @A-114-Desk check", true},
    {"check ChargingPoint", "check-chargingpoint@T [23 10:00,24 00:00] 2m p0 @ChargingPoint check", true},
    {"check hall-a-120 tomorrow at 08:00", "check-hall-a-120@T [24 08:00,24 08:30] 2m p0 @Hall-A-120 check", true},
    {"check A-123 on 2026-11-25 before 09:00", "check-a-123@T [25 00:00,25 09:00] 2m p0 @A-123 check", true},
    {"patrol Hall-West every 30 minutes from 08:00 to 18:00 on weekdays",
     "routine patrol-hall-west 08:00-18:00 every 30m mon,tue,wed,thu,fri 2m p0 @Hall-West patrol", true},
    {"check the exits daily at 07:00",
     "routine check-exit-west 07:00-07:30 daily 2m p0 @Exit-West check; "
     "routine check-exit-east 07:00-07:30 daily 2m p0 @Exit-East check",
     true},
    {"check the west exit every hour between 08:00 and 12:00",
     "routine check-exit-west 08:00-12:00 every 1h daily 2m p0 @Exit-West check", true},
    {"check A-120 every monday", "routine check-a-120 00:00-24:00 mon 2m p0 @A-120 check", true},
    {"urgent check room A-114 every weekday after 17:00",
     "routine check-a-114 17:00-24:00 mon,tue,wed,thu,fri 2m p10 @A-114 check", true},
    {"cancel the red letter delivery", "cancel delivery 'red letter'", true},
    {"cancel the check of office A-123", "cancel check @A-123", true},
    {"cancel the patrol of the emergency exits", "cancel patrol @Exit-West,Exit-East", true},
    {"cancel task check-a-123@2026-11-23T10:00", "cancel task check-a-123@2026-11-23T10:00", true},
    // Times from now: as "at" that time (a window of 30 min).
    {"check A-123 in 10 minutes", "check-a-123@T [23 10:10,23 10:40] 2m p0 @A-123 check", true},
    {"check A-123 in 1 minute", "check-a-123@T [23 10:01,23 10:31] 2m p0 @A-123 check", true},
    {"check A-123 in half an hour", "check-a-123@T [23 10:30,23 11:00] 2m p0 @A-123 check", true},
    {"check A-123 in an hour", "check-a-123@T [23 11:00,23 11:30] 2m p0 @A-123 check", true},
    {"urgent: check the kitchen in 2 hours for 5 minutes", "check-a-117@T [23 12:00,23 12:30] 5m p10 @A-117 check",
     true},
    {"come to the library in ten minutes", "visit-a-110@T [23 10:10,23 10:40] 5m p0 @A-110 visit", true},
    {"deliver the red letter from A-111 to A-120 in 15 mins",
     "pickup-red-letter@T [23 10:15,23 10:45] 1m p0 @A-111 load pickup:red-letter@T 'red letter'; "
     "drop-red-letter@T [23 10:15,23 10:45] 1m p0 @A-120 unload drop:red-letter@T 'red letter' "
     "after:pickup-red-letter@T",
     true},
    // Lists of places: one task, or one routine, per place.
    {"check A-110 and A-120", "check-a-110@T [23 10:00,24 00:00] 2m p0 @A-110 check; "
                              "check-a-120@T [23 10:00,24 00:00] 2m p0 @A-120 check",
     true},
    {"patrol A-110 and A-120 every day at 9am",
     "routine patrol-a-110 09:00-09:30 daily 2m p0 @A-110 patrol; "
     "routine patrol-a-120 09:00-09:30 daily 2m p0 @A-120 patrol",
     true},
    {"check A-110, the kitchen, and Michael's desk before 15:00",
     "check-a-110@T [23 10:00,23 15:00] 2m p0 @A-110 check; check-a-117@T [23 10:00,23 15:00] 2m p0 @A-117 check; "
     "check-a-114-desk@T [23 10:00,23 15:00] 2m p0 @A-114-Desk check",
     true},
    {"check A-123, the emergency exits and the desk in A-120 in 10 minutes",
     "check-a-123@T [23 10:10,23 10:40] 2m p0 @A-123 check; "
     "check-exit-west@T [23 10:10,23 10:40] 2m p0 @Exit-West check; "
     "check-exit-east@T [23 10:10,23 10:40] 2m p0 @Exit-East check; "
     "check-a-120-desk@T [23 10:10,23 10:40] 2m p0 @A-120-Desk check",
     true},
    {"go to A-110 and A-111 now", "visit-a-110@T now 5m p0 @A-110 visit; visit-a-111@T now 5m p0 @A-111 visit", true},
    {"cancel the check of A-110 and A-120", "cancel check @A-110,A-120", true},
};

const Case kRejected[] = {
    {"", "the command is empty", false},
    {"   ,.  ", "the command is empty", false},
    {"deliver the re\xB6\x8A letter from A-111 to A-120", "the command is not UTF-8 text (byte 14)", false},
    {"check A-123\x01", "the command holds a control character (byte 11)", false},
    {"fetch the red letter from A-111 to A-120", "I do not understand 'fetch'", false},
    {"deliver the red letter from A-111 to A-121", "no place called 'A-121'; nearest known places: A-120", false},
    {"put the red letter on the sofa in room A-111 on the desk in room A-120",
     "room A-111 has no place called 'sofa' (it has: meeting table)", false},
    {"check the desk", "'the desk' is in more than one room; say which: 'librarian's desk in A-110'", false},
    {"deliver the red letter to A-120", "needs the place to pick 'red letter' up from", false},
    {"deliver the red letter from A-111 to A-120 every day", "a delivery cannot repeat", false},
    {"check A-123 before lunch", "'before' needs a time of day such as 15:00, not 'lunch'", false},
    {"check A-123 between 20:15 and 20:00", "the second time must be later", false},
    {"check A-123 before 09:00", "ends at 2026-11-23T09:00, which is past (it is 2026-11-23T10:00)", false},
    {"come to A-110 now before 15:00", "'now' cannot go with a day or a time", false},
    {"check the emergency exits every 2 hours now", "cannot also be for 'now'", false},
    {"deliver the red letter from the emergency exits to A-120",
     "'the emergency exits' is 2 places; a delivery goes from one place to one place", false},
    {"deliver the red letter from A-120 to room A-120", "'A-120' and 'room A-120' are the same place", false},
    {"urgent", "the command has no verb", false},
    {"check A-123 every 10 hours between 08:00 and 12:00", "'every 10h' is longer than the daily window 08:00-12:00",
     false},
    {"cancel the red letter", "I do not understand 'cancel the red letter'", false},
    {"cancel the delivery of the red letter tomorrow", "a cancellation takes no priority and no time words", false},
    {"come A-110", "say 'come to PLACE'", false},
    {"check A-123 between 20:00 and 20:01 for 5 minutes", "is too short for the 5m it takes", false},
    {"check A-123 before 15:00 before 16:00", "'before' is given twice", false},
    {"check A-123 soon", "no place called 'A-123 soon'", false},
    {"check xyzzy", "no place called 'xyzzy'; nearest known places:", false},
    {"urgent: important: check A-123", "give one of 'urgent' and 'important'", false},
    {"put the red letter on A-111", "say 'put OBJECT on PLACE on PLACE'", false},
    {"check A-123 on sunday at 25:00", "'at' needs a time of day such as 15:00, not '25:00'", false},
    {"deliver from A-111 to A-120", "'deliver' needs an object", false},
    {"check A-123 on the roof", "no place called 'A-123 on the roof'", false},
    {"check A-123 after 18:00 before 09:00", "'after 18:00' and 'before 09:00' leave no time", false},
    {"check", "'check' needs a place", false},
    {"deliver the red letter from A-111 to A-120 with priority high",
     "'with priority' needs a whole number, not 'high'", false},
    {"check A-123 on 2026-11-20", "2026-11-20 is past (today is 2026-11-23)", false},
    {"check A-123 tomorrow on friday", "name the day once", false},
    {"check the emergency exits every 2 hours tomorrow", "cannot also be for 'now', 'today', 'tomorrow', a date",
     false},
    {"check A-123 in 10 minutes tomorrow", "'in 10m' is a time from now: it cannot go with a day or another time",
     false},
    {"check A-123 in 10 minutes at 15:00", "'in 10m' is a time from now", false},
    {"check A-123 every day in 10 minutes", "cannot also be for 'now', 'today', 'tomorrow', a date or a time from now",
     false},
    {"check A-123 in 0 minutes", "'in 0 minutes' must be later than now", false},
    {"check A-123 tomorrow in a while", "'in' needs a length such as '10 minutes' or 'half an hour', not 'a'", false},
    {"come to A-110 in 5 minutes now", "'now' cannot go with a day or a time", false},
    {"check A-110 and A-121", "no place called 'A-121'; nearest known places: A-120", false},
    {"check A-110 and room A-110", "the command names the place 'A-110' twice", false},
    {"patrol the exits and the east exit every day", "the command names the place 'Exit-East' twice", false},
    {"check the desk and A-110", "'the desk' is in more than one room; say which", false},
    {"check A-110 and", "no place called 'A-110 and'", false},
};

class Sentences : public ::testing::TestWithParam<Case> {};

TEST_P(Sentences, MeanWhatTheTableSays) {
  const Case& c = GetParam();
  auto command = parse_command(c.sentence, test::office_context());
  if (c.accepted) {
    ASSERT_TRUE(command.ok()) << c.sentence << ": " << command.error().message;
    EXPECT_EQ(describe(*command), with_tag(c.expected)) << c.sentence;
    // What it means is exactly what a task file holds: valid, and unchanged through the codec.
    EXPECT_TRUE(validate(command->tasks).ok()) << c.sentence;
    TaskFile file{*TimeZone::named("Europe/London"), command->tasks, command->routines};
    auto again = parse_task_file(encode(file).dump(), DocumentFormat::kJson, "again.json");
    ASSERT_TRUE(again.ok()) << c.sentence << ": " << again.error().message;
    EXPECT_EQ(again->tasks, command->tasks) << c.sentence;
    EXPECT_EQ(again->routines, command->routines) << c.sentence;
  } else {
    ASSERT_FALSE(command.ok()) << c.sentence << " was accepted as: " << describe(*command);
    EXPECT_NE(command.error().message.find(c.expected), std::string::npos)
        << c.sentence << "\n  error: " << command.error().message << "\n  expected to contain: " << c.expected;
    EXPECT_TRUE(command.error().code == ErrorCode::kInvalidInput || command.error().code == ErrorCode::kNotFound);
  }
}

INSTANTIATE_TEST_SUITE_P(Accepted, Sentences, ::testing::ValuesIn(kAccepted));
INSTANTIATE_TEST_SUITE_P(Rejected, Sentences, ::testing::ValuesIn(kRejected));

TEST(Sentences, TheTableIsLargeEnough) {
  EXPECT_GE(std::size(kAccepted) + std::size(kRejected), 40u);
}

TEST(Sentences, CancellationMatchesTheTasksItNames) {
  const auto ctx = test::office_context();
  auto letter = parse_command("deliver the red letter from A-111 to A-120 before 15:00", ctx);
  auto book = parse_command("deliver the green book from A-110 to A-114", ctx);
  auto check = parse_command("check office A-123 between 20:00 and 20:15", ctx);
  auto cancel = parse_command("cancel the delivery of the Red Letter", ctx);
  auto cancel_check = parse_command("cancel the check of A-123", ctx);
  ASSERT_TRUE(letter.ok() && book.ok() && check.ok() && cancel.ok() && cancel_check.ok());
  for (const auto& t : letter->tasks) EXPECT_TRUE(matches(*cancel->cancel, t)) << t.id;
  for (const auto& t : book->tasks) EXPECT_FALSE(matches(*cancel->cancel, t)) << t.id;
  EXPECT_FALSE(matches(*cancel->cancel, check->tasks[0]));
  EXPECT_TRUE(matches(*cancel_check->cancel, check->tasks[0]));
  EXPECT_FALSE(matches(*cancel_check->cancel, letter->tasks[0]));
  EXPECT_EQ(encode(*cancel->cancel).dump(), R"({"cancel":{"what":"delivery","object":"red letter"}})");
  // What encode() writes (a queued request's body) decodes back; anything else names the field.
  for (const Cancellation& c :
       {*cancel->cancel, *cancel_check->cancel,
        Cancellation{.what = Cancellation::What::kTask, .object = {}, .activity = {}, .nodes = {}, .id = "t1"}})
    EXPECT_EQ(decode_cancellation(encode(c)).value(), c);
  EXPECT_FALSE(decode_cancellation(Json{{"cancel", {{"what", "everything"}}}}).ok());
  EXPECT_FALSE(decode_cancellation(Json{{"cancel", {{"what", "activity"}, {"activity", "check"}}}}).ok());
  EXPECT_FALSE(decode_cancellation(Json::array()).ok());
  auto chair = parse_command("bring the office chair from A-110 to A-114", ctx);
  auto cancel_chair = parse_command("cancel the office chair delivery", ctx);
  ASSERT_TRUE(chair.ok() && cancel_chair.ok());
  EXPECT_TRUE(matches(*cancel_chair->cancel, chair->tasks[1]));
  EXPECT_FALSE(matches(*cancel->cancel, chair->tasks[1]));
}

// Any two different single places the office knows, named in any of their names, make a delivery
// between exactly their nodes; and the case of the letters never changes what a sentence means.
RC_GTEST_PROP(Sentences, DeliveriesGoBetweenExactlyThePlacesNamed, ()) {
  const Places& places = test::office().places;
  std::vector<std::string> singles;
  for (const auto& name : places.names()) {
    if (auto p = places.resolve(name); p && p->nodes.size() == 1) singles.push_back(name);
  }
  RC_PRE(singles.size() > 1);
  const auto from = *rc::gen::elementOf(singles);
  const auto to = *rc::gen::elementOf(singles);
  const auto from_node = places.resolve(from)->nodes.front();
  const auto to_node = places.resolve(to)->nodes.front();
  const std::string sentence = "deliver the red letter from " + from + " to " + to;
  auto c = parse_command(sentence, test::office_context());
  if (from_node == to_node) {
    RC_ASSERT(!c.ok());
    RC_ASSERT(c.error().message.find("are the same place") != std::string::npos);
    return;
  }
  RC_ASSERT(c.ok());
  RC_ASSERT(c->tasks.size() == 2u);
  RC_ASSERT(c->tasks[0].start_node == from_node);
  RC_ASSERT(c->tasks[1].start_node == to_node);
  std::string shouted = sentence;
  const auto flips = *rc::gen::container<std::vector<bool>>(shouted.size(), rc::gen::arbitrary<bool>());
  for (std::size_t i = 0; i < shouted.size(); ++i) {
    if (flips[i]) shouted[i] = static_cast<char>(std::toupper(static_cast<unsigned char>(shouted[i])));
  }
  auto again = parse_command(shouted, test::office_context());
  RC_ASSERT(again.ok());
  RC_ASSERT(describe(*again) == describe(*c));
}

// "in N minutes" is from the command's own "now", whatever its time of day: late in the evening it
// runs into the next day.
RC_GTEST_PROP(Sentences, InNMinutesIsThatLongAfterNow, ()) {
  const int n = *rc::gen::inRange(1, 1000);
  const bool in_hours = *rc::gen::arbitrary<bool>();
  const Duration later = in_hours ? hours(n) : minutes(n);
  CommandContext ctx = test::office_context();
  ctx.now += minutes(*rc::gen::inRange(0, 24 * 60));
  const std::string sentence = fmt::format("check A-123 in {} {}", n, in_hours ? "hours" : "minutes");
  auto c = parse_command(sentence, ctx);
  RC_ASSERT(c.ok());
  RC_ASSERT(c->tasks.size() == 1u);
  RC_ASSERT((c->tasks[0].window == TimeWindow{ctx.now + later, ctx.now + later + minutes(30)}));
}

// A list of any of the office's single places, joined with commas and "and", makes one task per
// place, in the order said, each exactly at its place's node.
RC_GTEST_PROP(Sentences, AListOfPlacesMakesOneTaskPerPlaceInOrder, ()) {
  const Places& places = test::office().places;
  std::vector<std::string> singles;
  for (const auto& name : places.names()) {
    if (auto p = places.resolve(name); p && p->nodes.size() == 1) singles.push_back(name);
  }
  const auto count = *rc::gen::inRange<std::size_t>(2, 6);
  std::vector<std::string> said;
  std::vector<std::string> nodes;
  while (said.size() < count) {
    const auto name = *rc::gen::elementOf(singles);
    const std::string node = places.resolve(name)->nodes.front();
    if (std::find(nodes.begin(), nodes.end(), node) != nodes.end()) continue;
    said.push_back(name);
    nodes.push_back(node);
  }
  std::string list = said.front();
  for (std::size_t i = 1; i < said.size(); ++i) list += (i + 1 == said.size() ? " and " : ", ") + said[i];
  auto c = parse_command("check " + list, test::office_context());
  RC_ASSERT(c.ok());
  std::vector<std::string> got;
  for (const auto& t : c->tasks) got.push_back(t.start_node);
  RC_ASSERT(got == nodes);
}

// The case the property found: two parts said with a comma between them ("meeting room, table in
// A-111") are not the known place their words make without it ("meeting room table in A-111"): a
// comma ends a part of a list, unless the known name holds the comma itself.
TEST(Sentences, ACommaEndsAPartOfAListUnlessAKnownNameHoldsIt) {
  auto c = parse_command("check meeting room, table in A-111 and west exit", test::office_context());
  ASSERT_TRUE(c.ok()) << c.error().message;
  std::vector<std::string> got;
  for (const auto& t : c->tasks) got.push_back(t.start_node);
  EXPECT_EQ(got, (std::vector<std::string>{"A-111", "A-111-Table", "Exit-West"}));

  auto doc = Document::parse("places:\n  - {name: \"Smith, Jones office\", node: A-123}\n", DocumentFormat::kYaml,
                             "places.yaml");
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto places = Places::decode(*doc, test::office().map);
  ASSERT_TRUE(places.ok()) << places.error().message;
  CommandContext ctx = test::office_context();
  ctx.places = &*places;
  auto named = parse_command("check Smith, Jones office and A-110", ctx);
  ASSERT_TRUE(named.ok()) << named.error().message;
  got.clear();
  for (const auto& t : named->tasks) got.push_back(t.start_node);
  EXPECT_EQ(got, (std::vector<std::string>{"A-123", "A-110"}));
}

// A place whose own name holds "and" is that place, never two; a list that can be cut into known
// places in two ways that mean different places is an error that shows both.
TEST(Sentences, AKnownNameWithAndIsNeverCutAndTwoReadingsAreAnError) {
  auto doc = Document::parse(R"(places:
  - {name: Tom and Anna's office, node: A-123}
  - {name: Tom, node: A-110}
  - {name: red and blue, node: A-110-Desk}
  - {name: blue and green, node: A-111-Table}
  - {name: red, node: A-114}
  - {name: blue, node: A-117}
  - {name: green, node: Exit-West}
people:
  - {name: Anna, place: A-120}
)",
                             DocumentFormat::kYaml, "places.yaml");
  ASSERT_TRUE(doc.ok()) << doc.error().message;
  auto places = Places::decode(*doc, test::office().map);
  ASSERT_TRUE(places.ok()) << places.error().message;
  CommandContext ctx = test::office_context();
  ctx.places = &*places;
  auto nodes = [&](const std::string& sentence) {
    auto c = parse_command(sentence, ctx);
    std::vector<std::string> out;
    if (!c) return std::vector<std::string>{"error: " + c.error().message};
    for (const auto& t : c->tasks) out.push_back(t.start_node);
    return out;
  };
  using V = std::vector<std::string>;
  EXPECT_EQ(nodes("check Tom and Anna's office"), V{"A-123"});
  EXPECT_EQ(nodes("check Tom and Anna's office and A-111"), (V{"A-123", "A-111"}));
  EXPECT_EQ(nodes("check A-111, Tom and Anna's office"), (V{"A-111", "A-123"}));
  EXPECT_EQ(nodes("check Tom and Anna"), (V{"A-110", "A-120"}));
  EXPECT_EQ(nodes("check Anna and Tom"), (V{"A-120", "A-110"}));
  auto two = parse_command("check red and blue and green", ctx);
  ASSERT_FALSE(two.ok());
  EXPECT_EQ(two.error().message,
            "'red and blue and green' can be read two ways: 'red' and 'blue and green', or 'red and blue' and 'green'")
      << two.error().message;
  std::string many = "check A-110";
  for (int i = 0; i < 45; ++i) many += " and A-110";
  auto c = parse_command(many, ctx);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("a list of more than 40 places is too long"), std::string::npos)
      << c.error().message;
}

TEST(Sentences, TooLongIsAnErrorNotAWait) {
  std::string s = "check ";
  while (s.size() <= kMaxSentence) s += "A-123 to ";
  auto c = parse_command(s, test::office_context());
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("the most read is 2000"), std::string::npos) << c.error().message;
}

TEST(Sentences, WithoutAPlacesFileOnlyNodeNamesResolve) {
  const Places bare = Places::from_map(test::office().map);
  CommandContext ctx = test::office_context();
  ctx.places = &bare;
  EXPECT_TRUE(parse_command("check A-123-Desk", ctx).ok());
  auto c = parse_command("check the desk in room A-123", ctx);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("nearest known places: A-123-Desk"), std::string::npos) << c.error().message;
}

}  // namespace
}  // namespace rondo::lang

namespace rondo::lang {
namespace {

// The sentence forms of a task written as a formula (issue 41): the formula each means, compared
// as the parser reads it (so spacing and redundant parentheses do not matter).
TEST(Sentences, SpecFormsMeanTheirFormulas) {
  const auto same = [](const std::string& got, const std::string& want) {
    auto a = ltl::parse_formula(got);
    auto b = ltl::parse_formula(want);
    return a.ok() && b.ok() && ltl::to_string(*a) == ltl::to_string(*b);
  };
  const std::pair<const char*, const char*> cases[] = {
      {"check A-110 then A-114 or A-120", R"(F ("A-110" & F ("A-114" | "A-120")))"},
      {"check A-110 and A-120 in any order", R"(F "A-110" & F "A-120")"},
      {"check A-120 without passing Hall-A-114", R"(!"Hall-A-114" U "A-120")"},
      {"patrol A-110 then A-123 avoiding A-111 and A-114",
       R"((!"A-111" & !"A-114") U ("A-110" & ((!"A-111" & !"A-114") U "A-123")))"},
      {"check A-110 or A-120", R"(F ("A-110" | "A-120"))"},
  };
  for (const auto& [sentence, formula] : cases) {
    auto c = parse_command(sentence, test::office_context());
    ASSERT_TRUE(c.ok()) << sentence << ": " << c.error().message;
    ASSERT_EQ(c->tasks.size(), 1u) << sentence;
    const Task& t = c->tasks.front();
    EXPECT_TRUE(t.start_node.empty()) << sentence;
    EXPECT_TRUE(same(t.spec, formula)) << sentence << ": " << t.spec;
    EXPECT_TRUE(validate(t).ok()) << sentence;
  }
  auto routine = parse_command("check Exit-West then Exit-East every weekday at 09:00", test::office_context());
  ASSERT_TRUE(routine.ok()) << routine.error().message;
  ASSERT_EQ(routine->routines.size(), 1u);
  EXPECT_TRUE(routine->routines.front().task.start_node.empty());
  EXPECT_TRUE(same(routine->routines.front().task.spec, R"(F ("Exit-West" & F "Exit-East"))"));
  // Nine places in any order pass the automaton's limit: refused, saying why.
  auto nine =
      parse_command("check A-110, A-111, A-114, A-117, A-120, A-123, Exit-West, Exit-East and Hall-West in any order",
                    test::office_context());
  ASSERT_FALSE(nine.ok());
  EXPECT_NE(nine.error().message.find("which is refused"), std::string::npos) << nine.error().message;
}

}  // namespace
}  // namespace rondo::lang
