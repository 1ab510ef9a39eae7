#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "app/cli_runner.h"
#include "rondo/core/document.h"

namespace rondo {
namespace {

using test::run_cli;
namespace fs = std::filesystem;

class TaskCommands : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rondo_task_cmd_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(TaskCommands, CheckAcceptsTheExample) {
  auto r = run_cli({"task", "check", "tests/data/tasks/office_day.yaml"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("ok: 3 task(s), 2 routine(s)"), std::string::npos) << r.out;
  auto j = run_cli({"task", "check", "tests/data/tasks/office_day.yaml", "--json"});
  EXPECT_EQ(Json::parse(j.out)["tasks"], 3);
}

TEST_F(TaskCommands, BadFilesExitWithTwoAndSayWhere) {
  struct Case {
    const char* name;
    std::string text;
    std::string expect;
  };
  const Case cases[] = {
      {"truncated.yaml", "tasks:\n  - id: a\n    window: {release: 2026", "truncated.yaml:3"},
      {"wrong_type.yaml", "tasks:\n  - id: a\n    kind: on-demand\n    duration: [1]\n",
       "wrong_type.yaml:4: tasks[0].duration: expected a duration"},
      {"backwards.yaml", "tasks:\n  - id: a\n    window: {release: 2026-01-02T00:00Z, deadline: 2026-01-01T00:00Z}\n",
       "backwards.yaml:3: tasks[0].window.deadline: deadline 2026-01-01T00:00:00Z is before the release"},
      {"garbage.json", "\x01\x02\xff{", "garbage.json:1: the text is not valid UTF-8"},
      {"broken.json", "{\"tasks\": [", "broken.json: [json.exception.parse_error"},
      {"always.yaml", "tasks:\n  - id: a\n    kind: on-demand\n    spec: F A & G B\n",
       "always.yaml:4: tasks[0].spec: position 7: 'G' (always) is outside the co-safe fragment"},
      {"nine.yaml",
       "tasks:\n  - id: a\n    kind: on-demand\n    spec: F a & F b & F c & F d & F e & F f & F g & F h & F i\n",
       "nine.yaml:4: tasks[0].spec: "},
  };
  for (const auto& c : cases) {
    auto r = run_cli({"task", "check", write(c.name, c.text).string()});
    EXPECT_EQ(r.exit_code, 2) << c.name;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << c.name << ": " << r.err;
  }
  auto missing = run_cli({"task", "check", (dir_ / "nope.yaml").string()});
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nope.yaml: no such file"), std::string::npos);
}

TEST_F(TaskCommands, ExpandMakesRoutineTasksForEachDay) {
  auto r = run_cli({"task", "expand", "tests/data/tasks/office_day.yaml", "--from", "2026-11-23", "--days", "7",
                    "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  // 3 tasks + 5 weekdays x (1 fire-door check + 5 exit checks).
  EXPECT_EQ(j["tasks"].size(), 3u + 5u * 6u);
  auto bad = run_cli({"task", "expand", "tests/data/tasks/office_day.yaml", "--from", "23/11/2026"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--from"), std::string::npos);
}

}  // namespace
}  // namespace rondo
