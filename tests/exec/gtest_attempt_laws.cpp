// The stopped attempts' share and law per edge (attempt_laws.h), learned from the traversal log and
// the "edge attempt stopped" observations; the pooled laws' equal-count group means.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "attempt_laws.h"
#include "plan/small_maps.h"

namespace rondo::exec {
namespace {

const Time kStart = Time{} + hours(24 * 16000);

Traversal ended(const std::string& edge, bool success) {
  return {.edge_id = edge, .from = edge.substr(0, 1), .to = edge.substr(2), .start = kStart,
          .duration = seconds(10), .success = success};
}

store::Observation stopped(const std::string& what, const std::string& edge, double seconds) {
  return {.what = what, .where = edge, .when = kStart, .value = seconds, .text = std::nullopt};
}

TEST(StoppedAttempts, ShareOfAllTheEdgesAttemptsAndTheLawOfTheSecondsRun) {
  const map::TopoMap m = plan::testing::small_map({"A", "B", "C"}, {"A>B", "B>C", "C>A"});
  const std::vector<Traversal> log = {ended("A_B", true), ended("A_B", false), ended("B_C", true),
                                      ended("A_B", true)};
  const std::vector<store::Observation> seen = {
      stopped(kStoppedAttempt, "A_B", 120.0),
      stopped(kStoppedAttempt, "C_A", 90.0),   // no ended attempt: every attempt stopped
      stopped(kStoppedAttempt, "C_A", 30.0),
      stopped("door_open", "B_C", 1.0),        // another kind
      stopped(kStoppedAttempt, "X_Y", 50.0),   // not an edge of the map
      stopped(kStoppedAttempt, "B_C", std::numeric_limits<double>::quiet_NaN()),
      stopped(kStoppedAttempt, "B_C", 0.0),
  };
  const std::vector<plan::StoppedAttempts> got = learn_stopped_attempts(m, log, seen, 4);
  ASSERT_EQ(got.size(), m.edge_count());
  const map::EdgeIndex ab = *m.find_edge("A_B");
  const map::EdgeIndex bc = *m.find_edge("B_C");
  const map::EdgeIndex ca = *m.find_edge("C_A");
  EXPECT_DOUBLE_EQ(got[ab].share, 0.25);  // 1 stopped of 3 ended + 1
  EXPECT_EQ(got[ab].law, (std::vector<plan::DurationPoint>{{120.0, 1.0}}));
  EXPECT_EQ(got[bc], plan::StoppedAttempts{});
  EXPECT_DOUBLE_EQ(got[ca].share, 1.0);
  EXPECT_EQ(got[ca].law, (std::vector<plan::DurationPoint>{{30.0, 0.5}, {90.0, 0.5}}));
}

TEST(StoppedAttempts, GroupMeansKeepTheMeanInEqualCountGroups) {
  std::vector<double> ratios = {8, 1, 2, 7, 3, 6, 4, 5};
  const auto law = group_means(ratios, 4);
  EXPECT_EQ(law, (std::vector<plan::DurationPoint>{{1.5, 0.25}, {3.5, 0.25}, {5.5, 0.25}, {7.5, 0.25}}));
  std::vector<double> none;
  EXPECT_TRUE(group_means(none, 4).empty());
}

}  // namespace
}  // namespace rondo::exec
