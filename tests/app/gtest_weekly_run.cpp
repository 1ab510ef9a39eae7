// The week learned live, on the simulated building (issue 37, point 2): four weeks of
// bench/weekly-closure (the G4S example, whose corridor WayPoint24-WayPoint28 is closed on
// Wednesday afternoons), with the live weekly term and without it (`weekly_half_life: null`). The
// executor's weekly memory chooses the term for the corridor, and in week 4 the robot fails fewer
// times inside the closure than without it (seed 1: 3 against 11). A long scenario: it runs in
// the normal build only.
#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <fstream>

#include "cli_runner.h"
#include "rondo/core/document.h"
#include "rondo/learn/weekly_memory.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_log.h"
#include "test_files.h"

namespace rondo {
namespace {

using test::kSanitized;

// Failed attempts on `edges` on local weekday `weekday` (0 = Monday) between the hours, per week of
// the run from Monday 2026-11-23 (Europe/London is UTC then).
std::array<int, 4> failed_in(const store::Store& db, const std::vector<std::string>& edges, int weekday, int from_h,
                             int to_h) {
  std::array<int, 4> weeks{};
  const Time start = *parse_time("2026-11-23T00:00:00Z");
  for (int w = 0; w < 4; ++w) {
    const Time day = start + hours(24 * (7 * w + weekday));
    for (const std::string& e : edges) {
      const auto found = store::find_traversals(db, {.edge_id = e, .from = day + hours(from_h), .until = day + hours(to_h)});
      EXPECT_TRUE(found) << found.error().message;
      if (!found) continue;
      const std::vector<Traversal>& list = *found;
      for (const Traversal& t : list) weeks[static_cast<std::size_t>(w)] += t.success ? 0 : 1;
    }
  }
  return weeks;
}

std::array<int, 4> corridor_failures(const std::string& deployment, const std::filesystem::path& out) {
  const auto r = test::run_cli({"run", deployment, "--days", "28", "--seed", "1", "--out", out.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  auto db = store::Store::open(out / "rondo.sqlite");
  EXPECT_TRUE(db) << db.error().message;
  if (!db) return {};
  return failed_in(*db, {"WayPoint24_WayPoint28", "WayPoint28_WayPoint24"}, 2, 13, 17);
}

TEST(WeeklyRun, InWeekFourTheTermKeepsTheRobotFromAWeeklyClosureMoreThanWithoutIt) {
  if (kSanitized) GTEST_SKIP() << "a long scenario: the normal build runs it";
  const std::filesystem::path with = test::fresh_dir("rondo-weekly-run", "with", /*create=*/false);
  const std::filesystem::path without = test::fresh_dir("rondo-weekly-run", "without", /*create=*/false);
  const std::array<int, 4> on = corridor_failures("bench/weekly-closure/deployment.yaml", with);
  const std::array<int, 4> off = corridor_failures("bench/weekly-closure/without-weekly-term.yaml", without);
  ASSERT_GT(on[0], 0) << "week 1 must meet the closure for the test to mean anything";
  EXPECT_EQ(on[0], off[0]) << "the term cannot act before it is chosen";
  EXPECT_LT(on[3] * 2, off[3]) << "failed attempts in the closure, weeks 1-4, with the term: " << on[0] << " " << on[1]
                               << " " << on[2] << " " << on[3] << "; without: " << off[0] << " " << off[1] << " "
                               << off[2] << " " << off[3];

  // The memory is in the store, and it holds the term for the corridor.
  auto db = store::Store::open(with / "rondo.sqlite");
  ASSERT_TRUE(db) << db.error().message;
  auto stored = store::get_meta(*db, "learn.weekly_memory");
  ASSERT_TRUE(stored && *stored);
  auto memory = learn::WeeklyMemory::from_json(Json::parse(**stored));
  ASSERT_TRUE(memory) << memory.error().message;
  EXPECT_TRUE(memory->choice("WayPoint24_WayPoint28", {}).weekly);
}

}  // namespace
}  // namespace rondo
