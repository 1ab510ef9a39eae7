// `rondo run` on the courier's office floor for a simulated fortnight: the deliveries it reports,
// and the loading times it learns against the simulated truth (issue 16, point 2). A long
// scenario: it runs in the normal build only, not again under the sanitizers.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cli_runner.h"
#include "rondo/core/document.h"
#include "test_files.h"

namespace rondo {
namespace {

using test::kSanitized;

TEST(OfficeRun, LoadingTimesLearnedOverAFortnightAreCloserToThePeopleThanTheDeclaredMinute) {
  if (kSanitized) GTEST_SKIP() << "a long scenario: the normal build runs it";
  const std::filesystem::path out = test::fresh_dir("rondo-office-run", "fortnight", /*create=*/false);
  const auto r = test::run_cli({"run", "examples/office/deployment.yaml", "--days", "14", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json report = Json::parse(test::slurp(out / "report.json"));
  ASSERT_TRUE(report.contains("loading_times"));
  ASSERT_TRUE(report.contains("deliveries"));
  EXPECT_GT(report["deliveries"]["jobs"].get<int>(), 20);
  EXPECT_GT(report["deliveries"]["delivered"].get<int>(), 0);
  EXPECT_LE(report["deliveries"]["delivered_late"].get<int>(), report["deliveries"]["delivered"].get<int>());
  EXPECT_GE(report["deliveries"]["mean_lateness_s"].get<double>(), 0.0);
  double learned_error = 0, declared_error = 0;
  int places = 0;
  for (const Json& t : report["loading_times"]) {
    if (t["samples"].get<int>() < 3) continue;
    const double truth = t["truth_s"].get<double>();
    learned_error += std::abs(t["learned_s"].get<double>() - truth) / truth;
    declared_error += std::abs(60.0 - truth) / truth;  // the requests declare 1 minute
    ++places;
  }
  ASSERT_GE(places, 5);
  EXPECT_LT(learned_error / places, 0.6 * declared_error / places)
      << "mean relative error learned " << learned_error / places << ", declared " << declared_error / places;
  // The robot sees the doors as it passes them, and learns when they are open.
  ASSERT_TRUE(report.contains("assumptions"));
  const Json& a = report["assumptions"];
  EXPECT_GT(a["door_observations"].get<int>(), 100);
  EXPECT_GE(a["broken"].get<int>(), 1);
  EXPECT_EQ(a["reschedules"].get<int>(), a["broken"].get<int>());
  EXPECT_TRUE(a["door_open_learned"].contains("A-120-door"));
}

}  // namespace
}  // namespace rondo
