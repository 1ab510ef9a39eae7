// `rondo eval travel` on the real Witham Wharf logs: the JSON shape of the paper's Table I, and
// issue 4's acceptance on the default split for the route estimates of the best episode row.
#include <gtest/gtest.h>

#include <set>

#include "app/cli_runner.h"
#include "rondo/core/document.h"

namespace rondo::plan {
namespace {

using rondo::test::run_cli;

const Json* find_row(const Json& rows, const std::string& training, const std::string& model,
                     const std::string& protocol, const std::string& estimate) {
  for (const Json& r : rows)
    if (r["training"] == training && r["model"] == model && r["protocol"] == protocol && r["estimate"] == estimate)
      return &r;
  return nullptr;
}

TEST(EvalTravelCommand, WithamTableOnTheDefaultSplit) {
  const auto r = run_cli({"eval", "travel", "--witham", "../shared/data/witham_wharf", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json j = Json::parse(r.out);
  const std::size_t journeys = j["journeys"].get<std::size_t>();
  EXPECT_GT(journeys, 500u);
  const Json& rows = j["rows"];
  ASSERT_EQ(rows.size(), 4u * 3u * 2u * 2u);
  std::set<std::string> trainings;
  for (const Json& row : rows) {
    trainings.insert(row["training"].get<std::string>());
    const std::size_t expected =
        row["estimate"] == "route" ? journeys : journeys - j["round_trips"].get<std::size_t>();
    EXPECT_EQ(row["count"].get<std::size_t>(), expected);
    EXPECT_LE(row["q10"].get<double>(), row["q25"].get<double>());
    EXPECT_LE(row["q75"].get<double>(), row["q90"].get<double>());
  }
  EXPECT_EQ(trainings, (std::set<std::string>{"none", "week1", "weeks1-2", "all"}));

  // Acceptance: the best of ours (all data before the split, online) on route estimates.
  const Json* ours = find_row(rows, "all", "episode", "online", "route");
  ASSERT_NE(ours, nullptr);
  EXPECT_LE((*ours)["mean_abs"].get<double>(), 0.8);
  EXPECT_GE((*ours)["q10"].get<double>(), -0.2);
  EXPECT_LE((*ours)["q90"].get<double>(), 2.0);
  for (const char* other : {"static", "fremen"}) {
    for (const char* protocol : {"offline", "online"}) {
      const Json* row = find_row(rows, "all", other, protocol, "route");
      ASSERT_NE(row, nullptr);
      EXPECT_LT((*ours)["mean_abs"].get<double>(), (*row)["mean_abs"].get<double>()) << other << " " << protocol;
      EXPECT_LT((*ours)["q90"].get<double>(), (*row)["q90"].get<double>()) << other << " " << protocol;
    }
  }
}

TEST(EvalTravelCommand, BadInputsExitTwo) {
  EXPECT_EQ(run_cli({"eval", "travel", "--witham", "no/such/dir"}).exit_code, 2);
  EXPECT_EQ(run_cli({"eval", "travel", "--witham", "../shared/data/witham_wharf", "--split", "soon"}).exit_code, 2);
  const auto late = run_cli({"eval", "travel", "--witham", "../shared/data/witham_wharf", "--split", "2030-01-01T00:00:00Z"});
  EXPECT_EQ(late.exit_code, 2);
  EXPECT_NE(late.err.find("no journey"), std::string::npos) << late.err;
  const auto zone = run_cli({"eval", "travel", "--witham", "../shared/data/witham_wharf", "--zone", "Mars/Olympus"});
  EXPECT_EQ(zone.exit_code, 2);
  EXPECT_NE(zone.err.find("--zone"), std::string::npos) << zone.err;
}

}  // namespace
}  // namespace rondo::plan
