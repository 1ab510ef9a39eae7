// The routing benchmarks' readers and solution writer: small instances in both formats, solved
// and checked; malformed files give an error naming the file, the line and the problem (table).
#include <gtest/gtest.h>

#include "rondo/schedule/fleet_checker.h"
#include "rondo/schedule/fleet_scheduler.h"
#include "rondo/schedule/vrp_benchmark.h"

namespace rondo::schedule {
namespace {

constexpr const char* kSolomon = R"(TINY

VEHICLE
NUMBER     CAPACITY
   3         20

CUSTOMER
CUST NO.  XCOORD.   YCOORD.    DEMAND   READY TIME  DUE DATE   SERVICE   TIME

    0      0          0          0          0       1000          0
    1      3          4         10          0        100         10
    2      6          8         10          0        100         10
    3     -3         -4         10         50        200         10
    4      0          5          5          0       1000          0
)";

constexpr const char* kLiLim = R"(3	10	1
0	0	0	0	0	1000	0	0	0
1	3	4	5	0	100	10	0	2
2	6	8	-5	0	200	10	1	0
3	-3	-4	7	0	300	10	0	4
4	0	-5	-7	0	400	10	3	0
)";

TEST(VrpBenchmark, ReadsSolomonAndSolvesIt) {
  auto p = parse_vrptw(kSolomon, "tiny.txt");
  ASSERT_TRUE(p.ok()) << p.error().message;
  ASSERT_TRUE(validate_fleet(*p).ok());
  EXPECT_EQ(p->robots.size(), 3u);
  EXPECT_EQ(p->tasks.size(), 4u);
  EXPECT_EQ(p->tasks[0].demand, 10);
  EXPECT_EQ(p->tasks[2].task.release, Time{} + 50 * kVrpUnit);
  EXPECT_DOUBLE_EQ(p->distance_between(0, 1), 5.0);
  const FleetPlan plan = FleetScheduler({.seed = 1}).solve(*p, PollBudgetStop(2000));
  ASSERT_TRUE(check_fleet_plan(*p, plan).ok()) << check_fleet_plan(*p, plan).summary();
  EXPECT_TRUE(plan.dropped.empty());
  // Capacity 20 holds two customers of 10: at least two vehicles.
  EXPECT_EQ(plan.vehicles, 2u);
  const std::string routes = format_routes(*p, plan);
  EXPECT_EQ(routes.rfind("Route 1:", 0), 0u) << routes;
  EXPECT_NE(routes.find("Route 2:"), std::string::npos) << routes;
}

TEST(VrpBenchmark, ReadsLiLimAndKeepsPickupsBeforeTheirDeliveries) {
  auto p = parse_pdptw(kLiLim, "tiny.pdp");
  ASSERT_TRUE(p.ok()) << p.error().message;
  ASSERT_TRUE(validate_fleet(*p).ok());
  ASSERT_TRUE(p->tasks[0].task.transfer);
  EXPECT_EQ(p->tasks[0].task.transfer->action, ItemAction::kPickup);
  EXPECT_EQ(p->tasks[1].task.transfer->action, ItemAction::kDrop);
  EXPECT_EQ(p->tasks[1].task.transfer->job, "1");
  const FleetPlan plan = FleetScheduler({.seed = 1}).solve(*p, PollBudgetStop(2000));
  ASSERT_TRUE(check_fleet_plan(*p, plan).ok()) << check_fleet_plan(*p, plan).summary();
  EXPECT_TRUE(plan.dropped.empty());
}

struct Malformed {
  const char* name;
  bool pdp;
  std::string text;
  std::string message;  // expected in the error
};

class VrpMalformed : public ::testing::TestWithParam<Malformed> {};

TEST_P(VrpMalformed, IsAnInputErrorNamingTheLine) {
  const Malformed& m = GetParam();
  auto p = m.pdp ? parse_pdptw(m.text, "bad.txt") : parse_vrptw(m.text, "bad.txt");
  ASSERT_FALSE(p.ok()) << m.name;
  EXPECT_EQ(p.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(p.error().message.find(m.message), std::string::npos) << m.name << ": " << p.error().message;
}

std::string solomon_with(const std::string& vehicle_line, const std::string& rows) {
  return "X\nVEHICLE\nNUMBER CAPACITY\n" + vehicle_line + "\nCUSTOMER\nCUST NO. XCOORD.\n" + rows;
}

INSTANTIATE_TEST_SUITE_P(
    Files, VrpMalformed,
    ::testing::Values(
        Malformed{"empty", false, "", "bad.txt:1: no VEHICLE section"},
        Malformed{"no header", false, "X\nVEHICLE\n3 20\n", "bad.txt:3: VEHICLE: expected the header"},
        Malformed{"one number", false, solomon_with("3", "0 0 0 0 0 10 0"), "bad.txt:4: VEHICLE: expected 2 numbers, found 1"},
        Malformed{"no vehicles", false, solomon_with("0 20", "0 0 0 0 0 10 0"), "bad.txt:4: VEHICLE: NUMBER: expected a whole number"},
        Malformed{"no customers", false, "X\nVEHICLE\nNUMBER CAPACITY\n3 20\n", "no CUSTOMER section"},
        Malformed{"no depot", false, solomon_with("3 20", ""), "CUSTOMER: no depot row"},
        Malformed{"short row", false, solomon_with("3 20", "0 0 0 0 0 10 0\n1 1 1 1 0 10"),
                  "bad.txt:8: customer row: expected 7 numbers, found 6"},
        Malformed{"text", false, solomon_with("3 20", "0 0 0 0 0 10 0\n1 1 one 1 0 10 0"),
                  "bad.txt:8: customer row: 'one' is not a number"},
        Malformed{"nan", false, solomon_with("3 20", "0 0 0 0 0 10 0\n1 1 nan 1 0 10 0"), "'nan' is not a number"},
        Malformed{"huge", false, solomon_with("3 20", "0 0 0 0 0 10 0\n1 1 1e300 1 0 10 0"), "out of range"},
        Malformed{"window", false, solomon_with("3 20", "0 0 0 0 0 10 0\n1 1 1 1 9 3 0"),
                  "bad.txt:8: customer 1: due time 3 before ready time 9"},
        Malformed{"negative demand", false, solomon_with("3 20", "0 0 0 0 0 10 0\n1 1 1 -1 0 10 0"), "negative demand"},
        Malformed{"twice", false, solomon_with("3 20", "0 0 0 0 0 10 0\n1 1 1 1 0 10 0\n1 2 2 1 0 10 0"),
                  "bad.txt:9: customer 1 is listed twice (first on line 8)"},
        Malformed{"pdp empty", true, "", "bad.txt:1: empty file"},
        Malformed{"pdp head", true, "3 10\n", "bad.txt:1: first line (vehicles capacity speed): expected 3 numbers"},
        Malformed{"pdp speed", true, "3 10 -1\n0 0 0 0 0 10 0 0 0\n", "speed: must not be negative"},
        Malformed{"pdp no partner", true, "3 10 1\n0 0 0 0 0 10 0 0 0\n1 1 1 1 0 10 0 0 0\n",
                  "bad.txt:3: task 1: exactly one of pickup and delivery"},
        Malformed{"pdp missing", true, "3 10 1\n0 0 0 0 0 10 0 0 0\n1 1 1 1 0 10 0 0 7\n",
                  "bad.txt:3: task 1: its delivery 7 does not exist"},
        Malformed{"pdp not back", true, "3 10 1\n0 0 0 0 0 10 0 0 0\n1 1 1 1 0 10 0 0 2\n2 1 1 -1 0 10 0 3 0\n3 1 1 1 0 10 0 0 2\n",
                  "task 1: task 2 does not name it back"},
        Malformed{"pdp sign", true, "3 10 1\n0 0 0 0 0 10 0 0 0\n1 1 1 -1 0 10 0 0 2\n2 1 1 1 0 10 0 1 0\n",
                  "task 1: a pickup with demand -1"}),
    [](const auto& param_info) {
      std::string n = param_info.param.name;
      for (char& c : n)
        if (c == ' ') c = '_';
      return n;
    });

// Several of Li & Lim's files (lc104, lr107, ...) hold 0 as the speed: it is not used.
TEST(VrpBenchmark, ALiLimSpeedOfZeroIsRead) {
  std::string text = kLiLim;
  text.replace(0, 6, "3\t10\t0");
  auto p = parse_pdptw(text, "tiny.pdp");
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_EQ(p->robots.front().speed_factor, 1.0);
}

TEST(VrpBenchmark, AMissingFileIsAnError) {
  auto p = load_vrptw("/nonexistent/R101.txt");
  ASSERT_FALSE(p.ok());
  EXPECT_NE(p.error().message.find("R101.txt"), std::string::npos);
}

}  // namespace
}  // namespace rondo::schedule
