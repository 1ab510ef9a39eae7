// `rondo task add SENTENCE`: what it prints, that its JSON is a task file rondo reads back, exit
// code 2 naming the words it could not read; and the example floor examples/office runs.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "rondo/core/document.h"

namespace rondo {
namespace {

using test::run_cli;
using ::testing::HasSubstr;

std::vector<std::string> add(std::vector<std::string> words) {
  std::vector<std::string> args = {"task", "add"};
  args.insert(args.end(), words.begin(), words.end());
  for (const char* a :
       {"--map", "examples/office/map.yaml", "--places", "examples/office/places.yaml", "--at", "2026-11-23T10:00"}) {
    args.emplace_back(a);
  }
  return args;
}

TEST(TaskAdd, PrintsTheTasksOfTheSentence) {
  auto r = run_cli(add({"deliver the red letter from A-111 to A-120 before 15:00"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("pickup-red-letter@2026-11-23T10:00   2026-11-23T10:00:00+00:00  "
                               "2026-11-23T15:00:00+00:00"));
  EXPECT_THAT(r.out, HasSubstr("drop-red-letter@2026-11-23T10:00"));
  // The words may also come unquoted, as several arguments.
  auto words = run_cli(add({"urgent:", "come", "to", "A-110", "now"}));
  ASSERT_EQ(words.exit_code, 0) << words.err;
  EXPECT_THAT(words.out, HasSubstr("visit-a-110@2026-11-23T10:00         now"));
  auto routine = run_cli(add({"check the emergency exits every 2 hours", "--dry-run"}));
  ASSERT_EQ(routine.exit_code, 0) << routine.err;
  EXPECT_THAT(routine.out, HasSubstr("routine check-exit-east: check the emergency exits (Exit-East) at Exit-East, "
                                     "00:00-24:00, every 2h, daily"));
}

TEST(TaskAdd, JsonIsATaskFileThatReadsBack) {
  auto r = run_cli(add({"put the red letter on the meeting table in room A-111 on the desk in room A-120", "--json"}));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["timezone"], "Europe/London");
  ASSERT_EQ(j["tasks"].size(), 2u);
  EXPECT_EQ(j["tasks"][0]["start_node"], "A-111-Table");
  EXPECT_EQ(j["tasks"][0]["delivery"]["role"], "pickup");
  EXPECT_EQ(j["tasks"][1]["after"][0], "pickup-red-letter@2026-11-23T10:00");
  const auto file = std::filesystem::temp_directory_path() / ("rondo-task-add-" + std::to_string(::getpid()) + ".json");
  std::ofstream(file) << r.out;
  auto check = run_cli({"task", "check", file.string()});
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("ok: 2 task(s), 0 routine(s)"));
  std::filesystem::remove(file);
  auto cancel = run_cli(add({"cancel the delivery of the red letter", "--json"}));
  ASSERT_EQ(cancel.exit_code, 0) << cancel.err;
  EXPECT_EQ(Json::parse(cancel.out)["cancel"]["object"], "red letter");
}

TEST(TaskAdd, WordsItCannotReadAreExitCode2NamingThem) {
  auto place = run_cli(add({"deliver the red letter from A-111 to A-121"}));
  EXPECT_EQ(place.exit_code, 2);
  EXPECT_THAT(place.err, HasSubstr("rondo: error: 'deliver the red letter from A-111 to A-121': no place called "
                                   "'A-121'; nearest known places: A-120, A-123, A-111"));
  EXPECT_TRUE(place.out.empty());
  auto verb = run_cli(add({"fetch the red letter"}));
  EXPECT_EQ(verb.exit_code, 2);
  EXPECT_THAT(verb.err, HasSubstr("I do not understand 'fetch'"));
  auto at = run_cli({"task", "add", "check A-123", "--map", "examples/office/map.yaml", "--places",
                     "examples/office/places.yaml", "--at", "half past ten"});
  EXPECT_EQ(at.exit_code, 2);
  EXPECT_THAT(at.err, HasSubstr("--at:"));
  auto zone = run_cli({"task", "add", "check A-123", "--map", "examples/office/map.yaml", "--at", "2026-11-23T10:00Z"});
  EXPECT_EQ(zone.exit_code, 2);
  EXPECT_THAT(zone.err, HasSubstr("no time zone: give --time-zone ZONE, or time_zone in the places file"));
  auto bad_places = run_cli(
      {"task", "add", "check A-123", "--map", "examples/office/map.yaml", "--places", "examples/office/world.yaml"});
  EXPECT_EQ(bad_places.exit_code, 2);
  EXPECT_THAT(bad_places.err, HasSubstr("world.yaml:"));
  auto no_map = run_cli({"task", "add", "check A-123", "--map", "no/such/map.yaml", "--time-zone", "UTC"});
  EXPECT_EQ(no_map.exit_code, 2);
}

TEST(TaskAdd, TimeZoneOptionOverridesThePlacesFile) {
  auto r =
      run_cli({"task", "add", "check A-123 before 15:00", "--map", "examples/office/map.yaml", "--places",
               "examples/office/places.yaml", "--time-zone", "Europe/Paris", "--at", "2026-11-23 10:00", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["timezone"], "Europe/Paris");
  EXPECT_EQ(j["tasks"][0]["window"]["release"], "2026-11-23T09:00:00Z");
  EXPECT_EQ(j["tasks"][0]["window"]["deadline"], "2026-11-23T14:00:00Z");
}

TEST(OfficeExample, MapChecksAndTheDeploymentRuns) {
  auto check = run_cli({"map", "check", "examples/office/map.yaml"});
  EXPECT_EQ(check.exit_code, 0) << check.err;
  EXPECT_THAT(check.out, HasSubstr("0 warnings"));
  const auto out = std::filesystem::temp_directory_path() / ("rondo-office-run-" + std::to_string(::getpid()));
  std::filesystem::remove_all(out);
  auto run = run_cli({"run", "examples/office/deployment.yaml", "--days", "2", "--out", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream in(out / "report.json");
  const Json report = Json::parse(in);
  EXPECT_GT(report["tasks"]["completed"].get<int>(), 20);
  EXPECT_GT(report["navigation"]["attempts"].get<int>(), 100);
  std::filesystem::remove_all(out);
}

}  // namespace
}  // namespace rondo
