// cut_journeys: the chaining rule on hand-made logs (table-driven) and, as a property on random
// logs, that journeys partition the log and that exactly the chained neighbours share a journey.
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <algorithm>

#include "rondo/plan/journeys.h"

namespace rondo::plan {
namespace {

const Time kT0 = Time{} + hours(24 * 16000);

Traversal attempt(const std::string& from, const std::string& to, double start_s, double seconds, bool success) {
  return {.edge_id = from + "_" + to,
          .from = from,
          .to = to,
          .start = kT0 + from_seconds(start_s),
          .duration = from_seconds(seconds),
          .success = success};
}

struct Case {
  const char* name;
  std::vector<Traversal> log;
  std::vector<std::size_t> sizes;  // attempts per journey
};

TEST(Journeys, ChainingRule) {
  const std::vector<Case> cases = {
      {"success then onwards", {attempt("A", "B", 0, 10, true), attempt("B", "C", 11, 5, true)}, {2}},
      {"failure then retry from the same node", {attempt("A", "B", 0, 10, false), attempt("A", "B", 10, 10, true)}, {2}},
      {"start logged a second early", {attempt("A", "B", 0, 10.4, true), attempt("B", "C", 10, 5, true)}, {2}},
      {"pause longer than the gap", {attempt("A", "B", 0, 10, true), attempt("B", "C", 16, 5, true)}, {1, 1}},
      {"starts elsewhere", {attempt("A", "B", 0, 10, true), attempt("C", "D", 10, 5, true)}, {1, 1}},
      {"failure, then from the failed edge's end", {attempt("A", "B", 0, 10, false), attempt("B", "C", 10, 5, true)}, {1, 1}},
      {"out of order in the log", {attempt("B", "C", 11, 5, true), attempt("A", "B", 0, 10, true)}, {2}},
  };
  for (const Case& c : cases) {
    const auto js = cut_journeys(c.log);
    std::vector<std::size_t> sizes;
    for (const auto& j : js) sizes.push_back(j.attempts.size());
    EXPECT_EQ(sizes, c.sizes) << c.name;
  }
}

TEST(Journeys, EndsDurationAndOutcome) {
  const std::vector<Traversal> log = {attempt("A", "B", 0, 10, true), attempt("B", "C", 11, 20, false),
                                      attempt("B", "C", 31, 20, true), attempt("C", "D", 100, 5, false)};
  const auto js = cut_journeys(log);
  ASSERT_EQ(js.size(), 2u);
  EXPECT_EQ(js[0].origin, "A");
  EXPECT_EQ(js[0].destination, "C");
  EXPECT_TRUE(js[0].succeeded);
  EXPECT_DOUBLE_EQ(js[0].seconds(), 51.0);
  EXPECT_EQ(js[0].attempts, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(js[1].destination, "C");  // the failed attempt left the robot where it was
  EXPECT_FALSE(js[1].succeeded);
}

Traversal by(std::string robot, Traversal t) {
  t.robot = std::move(robot);
  return t;
}

// A fleet's robots feed one log: their attempts interleave in time, and one robot's attempt that
// happens to start where another's ended continues nothing of the other's.
TEST(Journeys, EachRobotHasItsOwn) {
  const std::vector<Traversal> log = {
      by("r1", attempt("A", "B", 0, 10, true)), by("r2", attempt("B", "C", 10, 5, true)),
      by("r1", attempt("B", "D", 11, 5, true)), by("r2", attempt("C", "A", 15, 5, true))};
  const auto js = cut_journeys(log);
  ASSERT_EQ(js.size(), 2u);
  EXPECT_EQ(js[0].attempts, (std::vector<std::size_t>{0, 2}));
  EXPECT_EQ(js[0].destination, "D");
  EXPECT_EQ(js[1].attempts, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(js[1].origin, "B");
  EXPECT_EQ(js[1].destination, "A");
}

RC_GTEST_PROP(Journeys, PartitionTheLogAndFollowTheRule, ()) {
  const std::vector<std::string> nodes = {"A", "B", "C"};
  // One robot, or two whose attempts interleave.
  const std::vector<std::string> robots =
      *rc::gen::element(std::vector<std::string>{""}, std::vector<std::string>{"r1", "r2"});
  const int n = *rc::gen::inRange(0, 40);
  std::vector<Traversal> log;
  double t = 0;
  for (int i = 0; i < n; ++i) {
    const auto from = *rc::gen::elementOf(nodes);
    auto to = *rc::gen::elementOf(nodes);
    if (to == from) to = from == "A" ? "B" : "A";
    const double seconds = *rc::gen::inRange(1, 30);
    log.push_back(by(*rc::gen::elementOf(robots), attempt(from, to, t, seconds, *rc::gen::arbitrary<bool>())));
    t += seconds + *rc::gen::inRange(-1, 9);
  }
  const auto js = cut_journeys(log);
  std::vector<int> seen(log.size(), 0);
  const JourneyRule rule{};
  for (std::size_t k = 0; k < js.size(); ++k) {
    for (std::size_t a : js[k].attempts) ++seen[a];
    for (std::size_t i = 1; i < js[k].attempts.size(); ++i) {
      const Traversal& a = log[js[k].attempts[i - 1]];
      const Traversal& b = log[js[k].attempts[i]];
      const Duration gap = b.start - (a.start + a.duration);
      RC_ASSERT(gap >= -rule.tolerance);
      RC_ASSERT(gap <= rule.max_gap);
      RC_ASSERT(b.from == (a.success ? a.to : a.from));
    }
    for (std::size_t i = 1; i < js[k].attempts.size(); ++i)
      RC_ASSERT(log[js[k].attempts[i]].robot == log[js[k].attempts[0]].robot);
    if (k > 0) RC_ASSERT(js[k - 1].start <= js[k].start);
  }
  // Maximal: the first attempt of a journey does not continue its robot's journey before it.
  for (std::size_t k = 0; k < js.size(); ++k) {
    const Traversal& b = log[js[k].attempts.front()];
    const Journey* before = nullptr;
    for (std::size_t m = 0; m < k; ++m)
      if (log[js[m].attempts.front()].robot == b.robot) before = &js[m];
    if (before == nullptr) continue;
    const Traversal& a = log[before->attempts.back()];
    const Duration gap = b.start - (a.start + a.duration);
    RC_ASSERT(!(gap >= -rule.tolerance && gap <= rule.max_gap && b.from == (a.success ? a.to : a.from)));
  }
  RC_ASSERT(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
}

}  // namespace
}  // namespace rondo::plan
