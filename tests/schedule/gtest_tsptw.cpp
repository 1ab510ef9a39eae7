// The TSPTW reader: malformed files give errors naming the line; a Dumas instance reads as the
// data README says and solves to its proven optimum.
#include "rondo/schedule/tsptw.h"

#include <gtest/gtest.h>

#include "rondo/schedule/checker.h"
#include "rondo/schedule/default_scheduler.h"

namespace rondo::schedule {
namespace {

constexpr const char* kGood =
    "NAME : tiny\nTYPE : TSPTW\nDIMENSION : 3\nEDGE_WEIGHT_TYPE : EXPLICIT\nEDGE_WEIGHT_FORMAT : FULL_MATRIX\n"
    "EDGE_WEIGHT_SECTION\n0 5 9\n5 0 3\n9 3 0\nTIME_WINDOW_SECTION\n1 0 100\n2 0 10\n3 20 30\n"
    "DEPOT_SECTION\n1\n-1\nEOF\n";

TEST(Tsptw, ReadsDepotTasksWindowsAndReturn) {
  auto p = parse_tsptw(kGood, "tiny.tsptw");
  ASSERT_TRUE(p.ok()) << p.error().message;
  ASSERT_EQ(p->tasks.size(), 2U);
  EXPECT_EQ(p->tasks[0].id, "2");
  EXPECT_EQ(p->tasks[1].deadline_on, DeadlineOn::kStart);
  EXPECT_EQ(p->tasks[1].release - Time{}, seconds(20));
  EXPECT_EQ(p->tasks[1].latest_start() - Time{}, seconds(30));
  EXPECT_EQ(p->tasks[0].duration, Duration{0});
  ASSERT_TRUE(p->return_to);
  EXPECT_EQ(p->return_to->deadline - Time{}, seconds(100));
  EXPECT_EQ(p->travel->travel(1, 2, Time{}), seconds(3));
  const Schedule s = DefaultScheduler{}.solve(*p, NeverStop{});
  ASSERT_EQ(s.status, SolveStatus::kOptimal);
  EXPECT_EQ(tsptw_units(s.objective), 5 + 20);  // 2 at 5, 3 waits until 20
  EXPECT_TRUE(check_schedule(*p, s).ok());
}

TEST(Tsptw, MalformedFilesNameTheLine) {
  struct Case {
    std::string name;
    std::string text;
    std::string expected;  // a substring of the message
  };
  const std::string head = "NAME : x\nTYPE : TSPTW\nDIMENSION : 2\n";
  const std::vector<Case> cases = {
      {"empty", "", "missing DIMENSION"},
      {"matrix before dimension", "EDGE_WEIGHT_SECTION\n0 1\n", "tsptw:1: EDGE_WEIGHT_SECTION before DIMENSION"},
      {"short matrix", head + "EDGE_WEIGHT_SECTION\n0 1\n1\nTIME_WINDOW_SECTION\n",
       "tsptw:7: EDGE_WEIGHT_SECTION: entry (2, 2): expected an integer, found 'TIME_WINDOW_SECTION'"},
      {"word in matrix", head + "EDGE_WEIGHT_SECTION\n0 x\n1 0\n",
       "tsptw:5: EDGE_WEIGHT_SECTION: entry (1, 2): expected an integer, found 'x'"},
      {"negative travel", head + "EDGE_WEIGHT_SECTION\n0 -1\n1 0\n", "negative entry (1, 2)"},
      {"window reversed", head + "EDGE_WEIGHT_SECTION\n0 1\n1 0\nTIME_WINDOW_SECTION\n1 0 10\n2 9 3\n",
       "tsptw:9: TIME_WINDOW_SECTION: node 2: due time 3 before ready time 9"},
      {"node out of range", head + "EDGE_WEIGHT_SECTION\n0 1\n1 0\nTIME_WINDOW_SECTION\n1 0 10\n7 0 3\n",
       "tsptw:9: TIME_WINDOW_SECTION: node 7 out of range"},
      {"node twice", head + "EDGE_WEIGHT_SECTION\n0 1\n1 0\nTIME_WINDOW_SECTION\n1 0 10\n1 0 3\n",
       "node 1 listed twice"},
      {"no windows", head + "EDGE_WEIGHT_SECTION\n0 1\n1 0\nEOF\n", "missing TIME_WINDOW_SECTION"},
      {"wrong type", "TYPE : TSP\n", "tsptw:1: TYPE: expected TSPTW, found 'TSP'"},
      {"bad dimension", "DIMENSION : -3\n", "tsptw:1: DIMENSION: expected an integer from 1 to 100000, found '-3'"},
      {"unknown keyword", "COLOUR : blue\n", "tsptw:1: unknown keyword 'COLOUR'"},
      {"two depots", head + "DEPOT_SECTION\n1\n2\n-1\n", "only one depot"},
      {"other depot",
       head + "EDGE_WEIGHT_SECTION\n0 1\n1 0\nTIME_WINDOW_SECTION\n1 0 10\n2 0 3\nDEPOT_SECTION\n2\n-1\n",
       "the depot must be node 1"},
      {"explicit only", "EDGE_WEIGHT_TYPE : EUC_2D\n", "only EXPLICIT"},
      // Limits before work: the matrix must be present before it is allocated, values must fit.
      {"matrix larger than the file", head + "DIMENSION : 100000\nEDGE_WEIGHT_SECTION\n0 1\n",
       "tsptw:5: EDGE_WEIGHT_SECTION: DIMENSION 100000 needs 10000000000 entries, the file has only 2 tokens left"},
      {"windows larger than the file", head + "EDGE_WEIGHT_SECTION\n0 1\n1 0\nTIME_WINDOW_SECTION\n1 0\n",
       "TIME_WINDOW_SECTION: DIMENSION 2 needs 6 entries, the file has only 2 tokens left"},
      {"time near 1e16", head + "EDGE_WEIGHT_SECTION\n0 1\n1 0\nTIME_WINDOW_SECTION\n1 0 10000000000000000\n2 0 3\n",
       "node 1 due time: 10000000000000000 is out of range (at most 1000000000 seconds)"},
      {"weight past int64", head + "EDGE_WEIGHT_SECTION\n0 99999999999999999999\n1 0\n",
       "expected an integer, found '99999999999999999999'"},
      {"binary garbage", "\xff\xfe\x01 : x\n", "unknown keyword '\?\?\?'"},
  };
  for (const auto& c : cases) {
    auto p = parse_tsptw(c.text, "tsptw");
    ASSERT_FALSE(p.ok()) << c.name;
    EXPECT_NE(p.error().message.find(c.expected), std::string::npos) << c.name << ": " << p.error().message;
    EXPECT_EQ(p.error().code, ErrorCode::kInvalidInput) << c.name;
  }
}

TEST(Tsptw, MissingFileIsNotFound) {
  auto p = load_tsptw("../shared/data/trptw/dumas/no-such.tsptw");
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error().code, ErrorCode::kNotFound);
}

TEST(Tsptw, DumasN20W20Instance1SolvesToItsProvenOptimum) {
  auto p = load_tsptw("../shared/data/trptw/dumas/n20w20.001.tsptw");
  ASSERT_TRUE(p.ok()) << p.error().message;
  EXPECT_EQ(p->tasks.size(), 20U);
  const Schedule s = DefaultScheduler{}.solve(*p, NeverStop{});
  EXPECT_EQ(s.status, SolveStatus::kOptimal);
  EXPECT_EQ(tsptw_units(s.objective), 2528);  // reference.tsv, exact-optimum
  EXPECT_TRUE(check_schedule(*p, s).ok()) << check_schedule(*p, s).summary();
}

}  // namespace
}  // namespace rondo::schedule
