// The week learned live, on the simulated building (issue 37, point 2): four weeks of
// bench/weekly-closure (the G4S example, whose corridor WayPoint24-WayPoint28 is closed on
// Wednesday afternoons). The executor's weekly memory chooses the term for the corridor, and the
// robot's failed attempts inside the closure in week 4 are at most a tenth of week 1's. Without
// the live term (`weekly_half_life: null`) this run failed 102 of 193 times inside week 4's
// closure of the example. A long scenario: it runs in the normal build only.
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

TEST(WeeklyRun, AWeeklyClosureMetInWeekOneIsAvoidedInWeekFour) {
  if (kSanitized) GTEST_SKIP() << "a long scenario: the normal build runs it";
  const std::filesystem::path out = test::fresh_dir("rondo-weekly-run", "four-weeks", /*create=*/false);
  const auto r = test::run_cli(
      {"run", "bench/weekly-closure/deployment.yaml", "--days", "28", "--seed", "1", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto db = store::Store::open(out / "rondo.sqlite");
  ASSERT_TRUE(db) << db.error().message;
  const std::array<int, 4> corridor = failed_in(*db, {"WayPoint24_WayPoint28", "WayPoint28_WayPoint24"}, 2, 13, 17);
  ASSERT_GE(corridor[0], 20) << "week 1 must meet the closure for the test to mean anything";
  EXPECT_LE(corridor[3] * 10, corridor[0])
      << "failed attempts in the closure, weeks 1-4: " << corridor[0] << " " << corridor[1] << " " << corridor[2] << " "
      << corridor[3];

  // The memory is in the store, and it holds the term for the corridor.
  auto stored = store::get_meta(*db, "learn.weekly_memory");
  ASSERT_TRUE(stored && *stored);
  auto memory = learn::WeeklyMemory::from_json(Json::parse(**stored));
  ASSERT_TRUE(memory) << memory.error().message;
  EXPECT_TRUE(memory->choice("WayPoint24_WayPoint28", {}).weekly);
}

}  // namespace
}  // namespace rondo
