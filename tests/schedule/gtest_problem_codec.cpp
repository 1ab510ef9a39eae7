// Our problem format (docs/scheduling.md): a YAML and a JSON file read the same; bad input names
// the file, the line and the field.
#include "rondo/schedule/problem_codec.h"

#include <gtest/gtest.h>

#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"

namespace rondo::schedule {
namespace {

constexpr const char* kYaml = R"(locations: [dock, A-110, A-114]
travel:
  - [0, 60, 90]
  - [60, 0, 30]
  - [90, 30, 0]
robot:
  location: dock
  time: "2026-03-02T08:00:00Z"
  capacity: 2
tasks:
  - id: pick-book
    release: 0
    deadline: 1800
    duration: 1m
    start: A-110
    transfer: {job: book, action: pickup, appearance: green book}
  - id: drop-book
    release: 0
    deadline: "2026-03-02T09:00:00Z"
    duration: 30s
    start: A-114
    transfer: {job: book, action: drop, appearance: green book}
  - id: check-door
    release: 600
    deadline: 900
    deadline_on: start
    duration: 2m
    priority: 2
    start: A-110
    end: dock
    after: [pick-book]
)";

Result<Problem> parse(const std::string& text, DocumentFormat format = DocumentFormat::kYaml) {
  auto doc = Document::parse(text, format, "day.yaml");
  if (!doc) return doc.error();
  return decode_problem(*doc);
}

TEST(ProblemCodec, ReadsOurFormatAndSolvesIt) {
  auto p = parse(kYaml);
  ASSERT_TRUE(p.ok()) << p.error().message;
  ASSERT_EQ(p->tasks.size(), 3U);
  EXPECT_EQ(p->tasks[2].deadline_on, DeadlineOn::kStart);
  EXPECT_EQ(p->tasks[2].end_location, 0U);
  EXPECT_EQ(p->tasks[2].after, std::vector<std::size_t>{0});
  EXPECT_EQ(p->tasks[1].deadline, *parse_time("2026-03-02T09:00:00Z"));
  EXPECT_EQ(p->tasks[0].deadline, *parse_time("2026-03-02T08:30:00Z"));
  EXPECT_EQ(p->travel->travel(2, 1, p->robot.time), seconds(30));
  const Schedule s = DefaultScheduler{}.solve(*p, NeverStop{});
  EXPECT_EQ(s.status, SolveStatus::kOptimal);
  EXPECT_TRUE(check_schedule(*p, s).ok()) << check_schedule(*p, s).summary();
  const Json j = schedule_to_json(*p, s);
  EXPECT_EQ(j["status"], "optimal");
  EXPECT_EQ(j["order"].size(), 3U);
}

TEST(ProblemCodec, JsonReadsLikeYaml) {
  auto doc = Document::parse(kYaml, DocumentFormat::kYaml, "day.yaml");
  ASSERT_TRUE(doc.ok());
  auto from_json = parse(doc->json().dump(), DocumentFormat::kJson);
  ASSERT_TRUE(from_json.ok()) << from_json.error().message;
  EXPECT_EQ(from_json->tasks.size(), 3U);
}

TEST(ProblemCodec, BadInputNamesFileLineAndField) {
  struct Case {
    std::string name, from, to, expected;
  };
  const std::vector<Case> cases = {
      {"unknown location", "start: A-114", "start: B-200", "day.yaml:21: tasks[1].start: no location 'B-200'"},
      {"short travel row", "[60, 0, 30]", "[60, 0]", "day.yaml:4: travel[1]: expected 3 entries"},
      {"bad action", "action: drop", "action: throw", "tasks[1].transfer.action: must be 'pickup' or 'drop'"},
      {"unknown key", "priority: 2", "priority: 2\n    colour: red", "colour"},
      {"unknown after", "after: [pick-book]", "after: [fetch]", "no task 'fetch'"},
      {"window too short", "deadline: 1800", "deadline: 30", "tasks[0].deadline: the task cannot end"},
      {"cycle", "    transfer: {job: book, action: pickup, appearance: green book}",
       "    transfer: {job: book, action: pickup, appearance: green book}\n    after: [check-door]", "cycle"},
      {"drop without pickup", "job: book, action: pickup", "job: pen, action: pickup", "job 'book': dropped but never picked up"},
  };
  for (const auto& c : cases) {
    std::string text = kYaml;
    const auto at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.name;
    text.replace(at, c.from.size(), c.to);
    auto p = parse(text);
    ASSERT_FALSE(p.ok()) << c.name;
    EXPECT_NE(p.error().message.find(c.expected), std::string::npos) << c.name << ": " << p.error().message;
  }
}

}  // namespace
}  // namespace rondo::schedule
