// `rondo task add SENTENCE --data DIR`: the request is queued in the folder's store (what --json
// prints), --dry-run queues nothing, bad input is exit code 2 naming the problem, and a simulated
// run on the folder takes every queued request at its start: tasks added, a cancellation applied,
// a request it cannot carry out rejected in the event log with its reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "cli_runner.h"
#include "rondo/core/document.h"
#include "rondo/store/events.h"
#include "rondo/store/requests.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/task_table.h"
#include "test_files.h"

namespace rondo {
namespace {

using test::run_cli;
using ::testing::HasSubstr;

std::vector<std::string> add(const std::string& sentence, const std::filesystem::path& data,
                             std::vector<std::string> more = {}) {
  std::vector<std::string> args = {"task",
                                   "add",
                                   sentence,
                                   "--map",
                                   "examples/office/map.yaml",
                                   "--places",
                                   "examples/office/places.yaml",
                                   "--at",
                                   "2026-11-23T10:00",
                                   "--data",
                                   data.string()};
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// A folder with an empty store of the latest schema (as a run or a service makes it).
std::filesystem::path folder_with_store(const std::string& name) {
  const auto dir = test::fresh_dir("rondo-task-queue-test", name);
  EXPECT_TRUE(store::Store::open(dir / "rondo.sqlite").ok());
  return dir;
}

std::vector<store::RequestRow> requests_in(const std::filesystem::path& dir) {
  auto db = store::Store::open(dir / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  EXPECT_TRUE(db.ok());
  auto rows = store::list_requests(*db);
  EXPECT_TRUE(rows.ok());
  return rows.ok() ? *rows : std::vector<store::RequestRow>{};
}

TEST(TaskQueue, QueuesWhatTheSentenceMeansAndDryRunQueuesNothing) {
  const auto dir = folder_with_store("queue");
  const std::string sentence = "deliver the red letter from A-111 to A-120 before 15:00";
  auto dry = run_cli(add(sentence, dir, {"--dry-run"}));
  ASSERT_EQ(dry.exit_code, 0) << dry.err;
  EXPECT_TRUE(requests_in(dir).empty());
  auto json = run_cli(add(sentence, dir, {"--json"}));
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_THAT(json.err, HasSubstr("queued as request 1 in"));
  auto cancel = run_cli(add("cancel the delivery of the red letter", dir));
  ASSERT_EQ(cancel.exit_code, 0) << cancel.err;
  EXPECT_THAT(cancel.out, HasSubstr("cancel the delivery of 'red letter'"));
  const auto rows = requests_in(dir);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].sentence, sentence);
  EXPECT_EQ(rows[0].source, "words");
  EXPECT_EQ(rows[0].body, Json::parse(json.out));  // what --json prints
  EXPECT_FALSE(rows[0].taken.has_value());
  EXPECT_EQ(rows[1].body["cancel"]["object"], "red letter");
}

TEST(TaskQueue, BadInputIsExitCode2NamingTheProblemAndQueuesNothing) {
  const auto none = test::fresh_dir("rondo-task-queue-test", "no-store");
  auto missing = run_cli(add("check A-123", none));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("no rondo store there"));
  EXPECT_FALSE(std::filesystem::exists(none / "rondo.sqlite"));
  const auto dir = folder_with_store("bad");
  auto routine = run_cli(add("check the emergency exits every 2 hours", dir));
  EXPECT_EQ(routine.exit_code, 2);
  EXPECT_THAT(routine.err, HasSubstr("makes routines, which cannot be queued"));
  auto words = run_cli(add("deliver the red letter from A-111 to A-121", dir));
  EXPECT_EQ(words.exit_code, 2);
  EXPECT_THAT(words.err, HasSubstr("no place called 'A-121'"));
  EXPECT_TRUE(requests_in(dir).empty());
  {
    auto db = store::Store::open(dir / "rondo.sqlite");
    ASSERT_TRUE(db.ok());
    ASSERT_TRUE(store::set_meta(*db, "run.finished", "true").ok());
  }
  auto finished = run_cli(add("check A-123", dir));
  EXPECT_EQ(finished.exit_code, 2);
  EXPECT_THAT(finished.err, HasSubstr("the run there is finished"));
  EXPECT_TRUE(requests_in(dir).empty());
}

TEST(TaskQueue, ASimulatedRunTakesTheQueuedRequestsAtItsStart) {
  const auto dir = folder_with_store("run");
  ASSERT_EQ(run_cli(add("deliver the red letter from A-111 to A-120 before 15:00", dir)).exit_code, 0);
  ASSERT_EQ(run_cli(add("deliver the red letter from A-111 to A-120 before 15:00", dir)).exit_code, 0);  // again
  ASSERT_EQ(run_cli(add("check office A-123 between 20:00 and 20:15", dir)).exit_code, 0);
  ASSERT_EQ(run_cli(add("cancel the check of A-123", dir)).exit_code, 0);
  ASSERT_EQ(run_cli(add("cancel the delivery of the blue pen", dir)).exit_code, 0);
  auto run = run_cli({"run", "examples/office/deployment.yaml", "--days", "1", "--out", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = requests_in(dir);
  ASSERT_EQ(rows.size(), 5u);
  for (const auto& r : rows) EXPECT_TRUE(r.taken.has_value()) << r.id;
  EXPECT_EQ(rows[0].outcome, "added 2 task(s)");
  EXPECT_THAT(rows[1].outcome, HasSubstr("rejected: task pickup-red-letter@2026-11-23T10:00: the id is already taken"));
  EXPECT_EQ(rows[2].outcome, "added 1 task(s)");
  EXPECT_EQ(rows[3].outcome, "applied: 1 task(s) cancelled");
  EXPECT_EQ(rows[4].outcome, "rejected: no task that is not over yet matches it");
  auto db = store::Store::open(dir / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok());
  auto letter = store::get_task(*db, "drop-red-letter@2026-11-23T10:00");
  ASSERT_TRUE(letter.ok());
  EXPECT_EQ(letter->source, "words");
  EXPECT_EQ(store::get_task(*db, "check-a-123@2026-11-23T10:00")->state, "cancelled");
  auto events = store::read_events(*db);
  ASSERT_TRUE(events.ok());
  int rejected = 0;
  for (const store::Event& e : *events) {
    if (e.subject != store::Subject::kRequest || e.event != "rejected") continue;
    ++rejected;
    EXPECT_EQ(e.code, "invalid request");
    EXPECT_THAT(e.about, HasSubstr("request "));
  }
  EXPECT_EQ(rejected, 2);
}

}  // namespace
}  // namespace rondo
