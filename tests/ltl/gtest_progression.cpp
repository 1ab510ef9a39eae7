// The canonical form and progression, on hand-worked formulas.
#include <gtest/gtest.h>

#include <string>

#include "rondo/ltl/parser.h"
#include "rondo/ltl/progression.h"

namespace rondo::ltl {
namespace {

Formula read(const std::string& text) { return parse_formula(text).value(); }
std::string canon(const std::string& text) { return to_string(canonical(read(text))); }

TEST(Canonical, FoldsConstantsSortsAndRemovesRepeats) {
  EXPECT_EQ(canon("F b & F a & F b & true"), "F a & F b");
  EXPECT_EQ(canon("F b | F a | F b | false"), "F a | F b");
  EXPECT_EQ(canon("F a & false"), "false");
  EXPECT_EQ(canon("F a | true"), "true");
  EXPECT_EQ(canon("X false"), "false");
  EXPECT_EQ(canon("X true"), "X true");  // needs one more node: not true
  EXPECT_EQ(canon("F F a"), "F a");
  EXPECT_EQ(canon("F true | X a"), "true");
  EXPECT_EQ(canon("a U true"), "true");
  EXPECT_EQ(canon("a U false"), "false");
  EXPECT_EQ(canon("false U F a"), "F a");
  EXPECT_EQ(canon("true U a"), "F a");
  EXPECT_EQ(canon("F a U F a"), "F a");
}

TEST(Canonical, KnowsTheRobotIsAtOneNodeAtATime) {
  EXPECT_EQ(canon("X (a & b)"), "false");
  EXPECT_EQ(canon("X (a & !a)"), "false");
  EXPECT_EQ(canon("X (a & !b & !c)"), "X a");
  EXPECT_EQ(canon("X (!a | b | c)"), "X !a");
  EXPECT_EQ(canon("X (!a | a)"), "X (a | !a)");  // not true: the end satisfies neither
  EXPECT_EQ(canon("X (!a | !b | c)"), "X (!a | !b)");
  EXPECT_EQ(canon("F (a & b)"), "false");
}

TEST(Progress, StepsThroughTheIssueExamples) {
  const Formula both = canonical(read("F WayPoint5 & F WayPoint7"));
  EXPECT_EQ(to_string(progress(both, "WayPoint5")), "F WayPoint7");
  EXPECT_EQ(progress(both, std::nullopt), both);
  EXPECT_EQ(progress(progress(both, "WayPoint7"), "WayPoint5"), Formula::truth());

  const Formula avoid = canonical(read("!WayPoint12 U Station"));
  EXPECT_EQ(progress(avoid, "WayPoint1"), avoid);
  EXPECT_EQ(progress(avoid, "WayPoint12"), Formula::falsity());
  EXPECT_EQ(progress(avoid, "Station"), Formula::truth());

  const Formula then = canonical(read("F (WayPoint3 & F (WayPoint5 | WayPoint9))"));
  EXPECT_EQ(to_string(progress(then, "WayPoint3")),
            "F (WayPoint3 & F (WayPoint5 | WayPoint9)) | F (WayPoint5 | WayPoint9)");
  EXPECT_EQ(progress(progress(then, "WayPoint3"), "WayPoint9"), Formula::truth());
}

}  // namespace
}  // namespace rondo::ltl
