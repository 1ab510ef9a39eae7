// Pages of tasks by filter (task_table.h: find_tasks, as GET /api/v1/tasks asks them), the counts
// by state (and by robot), and the changes of a task's robot and definition, on both backends: the window filter
// compares the task JSON's times as times (SQLite's julianday, PostgreSQL's timestamptz), which
// the dialect writes differently.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rondo/store/task_table.h"
#include "store/store_backends.h"

namespace rondo::store {
namespace {

Time at(const char* text) {
  return parse_time(text).value();
}

// A task with a window [release, deadline] (times as the codec writes them), or none.
TaskRow task(const std::string& id, const std::string& state, const std::string& source, const char* added,
             std::optional<std::pair<const char*, const char*>> window) {
  Json j = {{"id", id}, {"name", "check"}};
  if (window) j["window"] = {{"release", window->first}, {"deadline", window->second}};
  TaskRow r{id, std::move(j), state, at(added), at(added)};
  r.source = source;
  return r;
}

std::vector<std::string> ids(const TaskPage& page) {
  std::vector<std::string> out;
  for (const TaskRow& r : page.rows) out.push_back(r.id);
  return out;
}

class TaskPages : public testing::BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (HasFatalFailure()) return;
    db_.emplace(open_store());
    const std::vector<TaskRow> rows{
        task("morning", "queued", "routine", "2026-11-23T07:00:00Z", {{"2026-11-23T08:00:00Z", "2026-11-23T09:00:00Z"}}),
        // Released on the second: "12:00:00Z" is before 12:00:00.200 as a time, after
        // "12:00:00.200Z" as text ('Z' > '.').
        task("noon", "succeeded", "api", "2026-11-23T07:01:00Z", {{"2026-11-23T12:00:00Z", "2026-11-23T13:00:00Z"}}),
        task("evening", "queued", "api", "2026-11-23T07:02:00Z", {{"2026-11-23T18:00:00Z", "2026-11-23T19:00:00Z"}}),
        task("now", "queued", "words", "2026-11-23T10:30:00Z", std::nullopt),
    };
    ASSERT_TRUE(add_tasks(*db_, rows, "added").ok());
  }
  std::optional<Store> db_;
};

TEST_P(TaskPages, FiltersByStateSourceAndWindow) {
  struct Case {
    const char* name;
    TaskFilter filter;
    long total;
    std::vector<std::string> ids;
  };
  const std::vector<Case> cases{
      {"all, in acceptance order", {}, 4, {"morning", "noon", "evening", "now"}},
      {"by state", {.state = "queued"}, 3, {"morning", "evening", "now"}},
      {"by source", {.source = "api"}, 2, {"noon", "evening"}},
      {"windows ending after 12:00:00.200", {.from = at("2026-11-23T12:00:00.200Z")}, 2, {"noon", "evening"}},
      {"windows starting before 12:00:00.200", {.to = at("2026-11-23T12:00:00.200Z")}, 2, {"morning", "noon"}},
      {"windows overlapping 08:30-12:30", {.from = at("2026-11-23T08:30:00Z"), .to = at("2026-11-23T12:30:00Z")},
       2, {"morning", "noon"}},
      {"and windowless tasks added then",
       {.from = at("2026-11-23T08:30:00Z"), .to = at("2026-11-23T12:30:00Z"), .windowless_by_added = true},
       3, {"morning", "noon", "now"}},
      {"queued and overlapping", {.state = "queued", .from = at("2026-11-23T08:30:00Z")}, 2, {"morning", "evening"}},
      {"a page", {.limit = 2, .offset = 1}, 4, {"noon", "evening"}},
  };
  for (const Case& c : cases) {
    const auto page = find_tasks(*db_, c.filter);
    ASSERT_TRUE(page.ok()) << c.name << ": " << page.error().message;
    EXPECT_EQ(page->total, c.total) << c.name;
    EXPECT_EQ(ids(*page), c.ids) << c.name;
  }
}

TEST_P(TaskPages, CountsByStateAndChangesRobotAndDefinition) {
  const auto counts = count_tasks_by_state(*db_);
  ASSERT_TRUE(counts.ok()) << counts.error().message;
  EXPECT_EQ(*counts, (std::map<std::string, long>{{"queued", 3}, {"succeeded", 1}}));

  ASSERT_TRUE(set_task_robot(*db_, "evening", "r2").ok());
  EXPECT_EQ(get_task(*db_, "evening")->robot, "r2");
  ASSERT_TRUE(set_task_robot(*db_, "evening", "").ok());
  EXPECT_EQ(get_task(*db_, "evening")->robot, "");
  EXPECT_EQ(set_task_robot(*db_, "ghost", "r2").error().code, ErrorCode::kNotFound);

  // By robot and state: a task allocated to none counts under "".
  ASSERT_TRUE(set_task_robot(*db_, "noon", "r2").ok());
  ASSERT_TRUE(set_task_robot(*db_, "morning", "r2").ok());
  const auto by_robot = count_tasks_by_robot(*db_);
  ASSERT_TRUE(by_robot.ok()) << by_robot.error().message;
  using Counts = std::map<std::string, std::map<std::string, long>>;
  EXPECT_EQ(*by_robot, (Counts{{"", {{"queued", 2}}}, {"r2", {{"queued", 1}, {"succeeded", 1}}}}));

  Json changed = get_task(*db_, "morning")->task;
  changed["priority"] = 7;
  ASSERT_TRUE(set_task_definition(*db_, "morning", changed).ok());
  EXPECT_EQ(get_task(*db_, "morning")->task, changed);
  EXPECT_EQ(set_task_definition(*db_, "ghost", changed).error().code, ErrorCode::kNotFound);

  ASSERT_TRUE(set_task_progress(*db_, "morning", Json{{"step", 2}}).ok());
  EXPECT_EQ(get_task(*db_, "morning")->progress, (Json{{"step", 2}}));
  ASSERT_TRUE(set_task_progress(*db_, "morning", Json()).ok());
  EXPECT_TRUE(get_task(*db_, "morning")->progress.is_null());
}

RONDO_ON_BOTH_BACKENDS(TaskPages);

}  // namespace
}  // namespace rondo::store
