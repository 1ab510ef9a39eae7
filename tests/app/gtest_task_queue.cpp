// `rondo task add SENTENCE --data DIR`: the request is queued in the folder's store (what --json
// prints), --dry-run queues nothing, bad input is exit code 2 naming the problem, and a simulated
// run on the folder takes every queued request at its start: tasks added, a cancellation applied,
// routines added and kept over a restart, a request it cannot carry out rejected in the event log
// with its reason; a killed run, resumed, takes nothing twice.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <thread>

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
  // Another delivery of the red letter in the same minute: its ids would be the first one's.
  ASSERT_EQ(run_cli(add("deliver the red letter from A-110 to A-114", dir)).exit_code, 0);
  auto run = run_cli({"run", "examples/office/deployment.yaml", "--days", "1", "--out", dir.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto rows = requests_in(dir);
  ASSERT_EQ(rows.size(), 6u);
  for (const auto& r : rows) EXPECT_TRUE(r.taken.has_value()) << r.id;
  EXPECT_EQ(rows[0].outcome, "added 2 task(s)");
  // The same sentence again (queued before the run took the first): nothing added, no clash.
  EXPECT_EQ(rows[1].outcome,
            "already queued: pickup-red-letter@2026-11-23T10:00, drop-red-letter@2026-11-23T10:00");
  EXPECT_EQ(rows[2].outcome, "added 1 task(s)");
  EXPECT_EQ(rows[3].outcome, "applied: 1 task(s) cancelled");
  EXPECT_EQ(rows[4].outcome, "rejected: no task that is not over yet matches it");
  EXPECT_EQ(rows[5].outcome, "added 2 task(s)");
  auto db = store::Store::open(dir / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok());
  auto letter = store::get_task(*db, "drop-red-letter@2026-11-23T10:00");
  ASSERT_TRUE(letter.ok());
  EXPECT_EQ(letter->source, "words");
  auto other = store::get_task(*db, "drop-red-letter@2026-11-23T10:00~2");
  ASSERT_TRUE(other.ok());
  EXPECT_EQ(other->task["start_node"], "A-114");
  EXPECT_EQ(other->task["after"], Json::array({"pickup-red-letter@2026-11-23T10:00~2"}));
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
  EXPECT_EQ(rejected, 1);
}

// The command line sees the folder's tasks: the same sentence again, when its tasks are there and
// still to do, queues nothing and says "already queued: ID" (exit 0); another one whose ids they
// hold gets ids of its own ("~2").
TEST(TaskQueue, TheSameSentenceAgainIsAlreadyQueuedAndAnotherGetsIdsOfItsOwn) {
  const auto dir = folder_with_store("again");
  auto first = run_cli(add("check office A-123", dir, {"--json"}));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  {  // as the executive takes it
    auto db = store::Store::open(dir / "rondo.sqlite");
    ASSERT_TRUE(db.ok());
    const Json task = Json::parse(first.out)["tasks"][0];
    const Time t0 = parse_time("2026-11-23T10:00:00Z").value();
    const store::TaskRow row{.id = task["id"].get<std::string>(),
                             .task = task,
                             .state = "queued",
                             .created = t0,
                             .updated = t0,
                             .source = "words"};
    ASSERT_TRUE(store::add_task(*db, row).ok());
    ASSERT_TRUE(store::take_request(*db, {1, t0, "added 1 task(s)"}).ok());
  }
  auto again = run_cli(add("check office A-123", dir));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_THAT(again.err, HasSubstr("already queued: check-a-123@2026-11-23T10:00 (in "));
  EXPECT_THAT(again.err, HasSubstr("nothing queued"));
  EXPECT_EQ(requests_in(dir).size(), 1u);
  auto other = run_cli(add("check office A-123 at 17:00", dir));
  ASSERT_EQ(other.exit_code, 0) << other.err;
  EXPECT_THAT(other.err, HasSubstr("queued as request 2 in"));
  EXPECT_THAT(other.err, HasSubstr(": 1 task(s): check-a-123@2026-11-23T10:00~2"));
  EXPECT_THAT(other.out, HasSubstr("check-a-123@2026-11-23T10:00~2"));
  const auto rows = requests_in(dir);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].body["tasks"][0]["id"], "check-a-123@2026-11-23T10:00~2");
}

TEST(TaskQueue, ARoutineIsQueuedAndTheOutputSaysWhat) {
  const auto dir = folder_with_store("routine-queued");
  auto r = run_cli(add("check the emergency exits every 2 hours", dir, {"--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("queued as request 1 in"));
  EXPECT_THAT(r.err, HasSubstr(": 2 routine(s): check-exit-west, check-exit-east"));
  auto t = run_cli(add("check office A-123 between 20:00 and 20:15", dir));
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_THAT(t.err, HasSubstr("queued as request 2 in"));
  EXPECT_THAT(t.err, HasSubstr(": 1 task(s): check-a-123@2026-11-23T10:00"));
  const auto rows = requests_in(dir);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].body, Json::parse(r.out));  // what --json prints: a task file with the routines
  EXPECT_EQ(rows[0].body["routines"].size(), 2u);
}

// The store's time of its latest event, once it has one.
std::optional<Time> stored_until(const std::filesystem::path& out) {
  if (!std::filesystem::exists(out / "rondo.sqlite")) return std::nullopt;
  auto db = store::Store::open(out / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  if (!db) return std::nullopt;
  auto end = store::log_end(*db);
  if (!end || end->seq == 0) return std::nullopt;
  return end->time;
}

// Runs `args` in a child process and kills it (SIGKILL) once its store is past `past`; false when
// it ended first.
bool run_and_kill_past(const std::vector<std::string>& args, const std::filesystem::path& out, Time past) {
  const pid_t child = ::fork();
  if (child < 0) return false;
  if (child == 0) {
    (void)run_cli(args);
    ::_exit(0);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(child, &status, WNOHANG) == child) return false;
    if (const auto t = stored_until(out); t && *t > past) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // polling for a condition, not a fixed wait
  }
  ::kill(child, SIGKILL);
  return ::waitpid(child, &status, 0) == child && WIFSIGNALED(status);
}

TEST(TaskQueue, ARoutineQueuedInWordsIsTakenOnceAndKeptOverARestart) {
  if (test::kSanitized) GTEST_SKIP() << "a kill and three simulated days: the normal build runs it";
  const auto dir = folder_with_store("routine-restart");
  const std::vector<std::string> run{"run", "examples/office/deployment.yaml", "--days", "3", "--out", dir.string()};
  // Taken at the first start: a routine of the sentence's own, and one the deployment has already.
  ASSERT_EQ(run_cli(add("check office A-123 every 3 hours between 10:00 and 17:00", dir)).exit_code, 0);
  ASSERT_EQ(run_cli(add("check the emergency exits every 2 hours", dir)).exit_code, 0);
  ASSERT_TRUE(run_and_kill_past(run, dir, parse_time("2026-11-24T06:00:00Z").value()))
      << "the run ended before it could be killed";
  // Queued while it is down: taken when it starts again. The first one again is a duplicate.
  ASSERT_EQ(run_cli(add("check the library every 4 hours", dir)).exit_code, 0);
  ASSERT_EQ(run_cli(add("check office A-123 every 3 hours between 10:00 and 17:00", dir)).exit_code, 0);
  const auto first = requests_in(dir);
  ASSERT_EQ(first.size(), 4u);
  ASSERT_TRUE(first[0].taken.has_value());
  EXPECT_FALSE(first[2].taken.has_value());
  auto resumed = run_cli(run);
  ASSERT_EQ(resumed.exit_code, 0) << resumed.err;
  EXPECT_THAT(resumed.err, HasSubstr("resumed the run"));

  const auto rows = requests_in(dir);
  ASSERT_EQ(rows.size(), 4u);
  for (const auto& r : rows) EXPECT_TRUE(r.taken.has_value()) << r.id;
  EXPECT_EQ(rows[0].outcome, "added 1 routine(s): check-a-123");
  EXPECT_EQ(rows[0].taken, first[0].taken);  // not taken again at the restart
  // Other routines than the deployment's of those names: routines of their own.
  EXPECT_EQ(rows[1].outcome, "added 2 routine(s): check-exit-west~2, check-exit-east~2");
  EXPECT_EQ(rows[2].outcome, "added 1 routine(s): check-a-110");
  EXPECT_EQ(rows[3].outcome, "already queued: check-a-123");

  auto db = store::Store::open(dir / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  ASSERT_TRUE(db.ok());
  // The routine taken in the first life makes its tasks on the first day and, kept in the store,
  // after the restart; the one taken at the restart from then on.
  for (const char* id : {"check-a-123@2026-11-23T10:00", "check-a-123@2026-11-23T16:00", "check-a-123@2026-11-25T10:00",
                         "check-a-110@2026-11-25T00:00", "check-a-110@2026-11-25T20:00"}) {
    auto task = store::get_task(*db, id);
    ASSERT_TRUE(task.ok()) << id;
    EXPECT_EQ(task->source, "routine") << id;
  }
  EXPECT_FALSE(store::get_task(*db, "check-a-110@2026-11-23T12:00").ok());  // taken on the second day
  auto events = store::read_events(*db);
  ASSERT_TRUE(events.ok());
  std::map<std::string, int> added;  // request events, by name
  std::map<std::string, int> task_added;
  for (const store::Event& e : *events) {
    if (e.subject == store::Subject::kRequest) ++added[e.event + " " + e.about];
    if (e.subject == store::Subject::kTask && e.code == "added") ++task_added[e.task_id];
  }
  EXPECT_EQ(added["routines added request 1"], 1);
  EXPECT_EQ(added["routines added request 2"], 1);
  EXPECT_EQ(added["routines added request 3"], 1);
  EXPECT_EQ(added["rejected request 4"], 0);
  for (const auto& [id, n] : task_added) EXPECT_EQ(n, 1) << id;
  auto kept = store::get_meta(*db, "serve.routines");
  ASSERT_TRUE(kept.ok() && kept->has_value());
  EXPECT_THAT(**kept, HasSubstr("check-a-123"));
  EXPECT_THAT(**kept, HasSubstr("check-a-110"));
}

}  // namespace
}  // namespace rondo
