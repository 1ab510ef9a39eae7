// `rondo run` on a folder that already holds a run: the same run resumes (after a kill), a
// finished one is not run again, another run's folder is refused and left as it was.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <map>
#include <set>
#include <thread>

#include "cli_runner.h"
#include "rondo/core/document.h"
#include "rondo/core/time.h"
#include "rondo/store/events.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"
#include "test_files.h"

namespace rondo {
namespace {

using test::slurp;
using ::testing::HasSubstr;

std::filesystem::path fresh_dir(const std::string& name) {
  return test::fresh_dir("rondo-resume-test", name, /*create=*/false);
}

// Every file under `dir` with its bytes.
std::map<std::string, std::string> snapshot(const std::filesystem::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) files[std::filesystem::relative(e.path(), dir).string()] = slurp(e.path());
  return files;
}

// The files that differ between two snapshots (added, removed or changed), by name.
std::vector<std::string> changed(const std::map<std::string, std::string>& a,
                                 const std::map<std::string, std::string>& b) {
  std::vector<std::string> names;
  for (const auto& [name, bytes] : a)
    if (!b.contains(name) || b.at(name) != bytes) names.push_back(name);
  for (const auto& [name, bytes] : b)
    if (!a.contains(name)) names.push_back(name);
  return names;
}

int sum_of(const Json& by_reason) {
  int n = 0;
  for (const auto& [reason, k] : by_reason.items()) n += k.get<int>();
  return n;
}

std::set<std::string> stored_ids(const std::filesystem::path& out) {
  auto store = store::Store::open(out / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly}).value();
  std::set<std::string> ids;
  const std::vector<store::TaskRow> tasks = store::list_tasks(store).value();
  for (const auto& t : tasks) ids.insert(t.id);
  return ids;
}

TEST(RunResume, AFolderOfAnotherRunIsRefusedAndLeftAsItWas) {
  const auto out = fresh_dir("other");
  ASSERT_EQ(test::run_cli({"run", "--days", "1", "--seed", "3", "--out", out.string()}).exit_code, 0);
  const auto before = snapshot(out);
  struct Case {
    std::vector<std::string> args;
    std::string says;
  };
  for (const Case& c : std::vector<Case>{
           {{"run", "--days", "1", "--seed", "1"}, "holds a run of seed 3, not 1"},
           {{"run", "--days", "2", "--seed", "3"}, "holds a run of 1 days, not 2"},
           {{"run", "examples/office/deployment.yaml", "--days", "1", "--seed", "3"}, "deployment g4s, not office"}}) {
    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"--out", out.string()});
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.says));
    EXPECT_THAT(r.err, HasSubstr(out.string()));
    EXPECT_THAT(changed(before, snapshot(out)), ::testing::IsEmpty()) << c.says;
  }
  std::filesystem::remove_all(out.parent_path());
}

TEST(RunResume, AFinishedRunSaysSoAndExitsZeroWithoutRunningAgain) {
  const auto out = fresh_dir("finished");
  ASSERT_EQ(test::run_cli({"run", "--days", "1", "--out", out.string()}).exit_code, 0);
  const auto before = snapshot(out);
  const auto r = test::run_cli({"run", "--days", "1", "--out", out.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("is a finished run"));
  EXPECT_THAT(changed(before, snapshot(out)), ::testing::IsEmpty());
  const auto j = test::run_cli({"run", "--days", "1", "--json", "--out", out.string()});
  EXPECT_EQ(j.exit_code, 0);
  EXPECT_EQ(Json::parse(j.out), Json::parse(slurp(out / "report.json")));
  auto store = store::Store::open(out / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly}).value();
  EXPECT_EQ(store::get_meta(store, "run.finished").value(), "true");
  std::filesystem::remove_all(out.parent_path());
}

// The latest event time in the folder's store; nothing while there is no store (or no schema) yet.
std::optional<Time> stored_until(const std::filesystem::path& out) {
  if (!std::filesystem::exists(out / "rondo.sqlite")) return std::nullopt;
  auto store = store::Store::open(out / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly});
  if (!store) return std::nullopt;
  auto end = store::log_end(*store);
  if (!end || end->seq == 0) return std::nullopt;
  return end->time;
}

TEST(RunResume, AKilledRunResumesToTheSameEndAndAccountsForEveryTask) {
  const auto out = fresh_dir("killed");
  const auto reference = fresh_dir("reference");
  const std::vector<std::string> args{"run", "--days", "3", "--out"};
  const Time start = parse_time("2026-11-23T00:00:00Z").value();

  // A child process runs it; once its store is past the first day it is killed with SIGKILL.
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::vector<std::string> a = args;
    a.push_back(out.string());
    (void)test::run_cli(a);
    ::_exit(0);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  int status = 0;
  bool ended = false;
  while (std::chrono::steady_clock::now() < deadline) {
    if (::waitpid(child, &status, WNOHANG) == child) {
      ended = true;
      break;
    }
    if (const auto t = stored_until(out); t && *t > start + hours(30)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));  // polling for a condition, not a fixed wait
  }
  if (!ended) {
    ::kill(child, SIGKILL);
    ASSERT_EQ(::waitpid(child, &status, 0), child);
  }
  ASSERT_TRUE(WIFSIGNALED(status)) << "the child finished before it could be killed";
  ASSERT_FALSE(std::filesystem::exists(out / "report.json"));

  std::vector<std::string> again = args;
  again.push_back(out.string());
  const auto r = test::run_cli(again);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("resumed the run"));
  std::vector<std::string> fresh = args;
  fresh.push_back(reference.string());
  ASSERT_EQ(test::run_cli(fresh).exit_code, 0);

  const Json report = Json::parse(slurp(out / "report.json"));
  const Json full = Json::parse(slurp(reference / "report.json"));
  const Json& t = report["tasks"];
  EXPECT_EQ(t["completed"].get<int>() + sum_of(t["failed"]) + sum_of(t["dropped"]) + sum_of(t["cancelled"]) +
                t["pending"].get<int>(),
            t["added"].get<int>());
  // The same tasks as the uninterrupted run (routines, one-off tasks, people's requests), each
  // added once, over the same span.
  EXPECT_EQ(stored_ids(out), stored_ids(reference));
  EXPECT_EQ(t["added"], full["tasks"]["added"]);
  EXPECT_EQ(report["from"], full["from"]);
  EXPECT_EQ(report["to"], full["to"]);
  auto store = store::Store::open(out / "rondo.sqlite", {.mode = store::OpenMode::kReadOnly}).value();
  std::map<std::string, int> added;
  const std::vector<store::Event> events = store::read_events(store).value();
  for (const auto& e : events)
    if (e.code == "added") ++added[e.task_id];
  for (const auto& [id, n] : added) EXPECT_EQ(n, 1) << id;
  EXPECT_EQ(added.size(), stored_ids(out).size());
  // Edge attempts come from the traversal log, so they cover the run from its start.
  EXPECT_GT(report["navigation"]["attempts"].get<int>(), full["navigation"]["attempts"].get<int>() / 2);
  EXPECT_EQ(store::get_meta(store, "run.finished").value(), "true");
  std::filesystem::remove_all(out.parent_path());
}

}  // namespace
}  // namespace rondo
