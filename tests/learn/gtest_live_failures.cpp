// How the online model reacts to a failed attempt and forgets it (issue 19, point 2): the live
// estimate drops at once, and how fast it recovers is learned from the log: after a closure that
// lasts hours it stays low for hours, after a person in the way for a minute it is back at once.
#include <gtest/gtest.h>

#include "rondo/learn/edge_models.h"
#include "series.h"

namespace rondo::learn {
namespace {

using testing::monday;

// An edge tried every 10 minutes for four weeks; after a failure the robot retries 30 s later.
// Each day at 10:00 it fails: with `closure_hours` > 0 every attempt and retry fails for that long
// (a closed corridor); otherwise one attempt fails and its retry succeeds (a person in the way).
std::vector<Traversal> daily_failures(double closure_hours) {
  std::vector<Traversal> log;
  for (int day = 0; day < 28; ++day) {
    for (int slot = 0; slot < 144; ++slot) {
      const Time start = monday() + hours(24 * day) + minutes(10 * slot);
      const double since_10 = (slot - 60) / 6.0;  // hours since 10:00
      const bool closed = closure_hours > 0 ? since_10 >= 0 && since_10 < closure_hours : slot == 60;
      log.push_back({"A_B", "A", "B", start, seconds(20), !closed, ""});
      if (closed) log.push_back({"A_B", "A", "B", start + seconds(50), seconds(20), closure_hours <= 0, ""});
    }
  }
  return log;
}

struct AfterFailure {
  double before, at_once, after_10_minutes, after_6_hours;
};

// Fits on the log, then lets a live view see one success and one failure on day 29 at 15:00 and
// asks for the success probability just before it, 30 s, 10 minutes and 6 hours after it.
AfterFailure react(const std::vector<Traversal>& log) {
  const std::vector<EdgeSpec> edges = {{"A_B", 20}};
  auto models = *EdgeModels::fit(edges, log);
  LiveEdgeModels live(models);
  const Time t = monday() + hours(24 * 28 + 15);
  live.observe({"A_B", "A", "B", t - minutes(10), seconds(20), true, ""});
  AfterFailure out{};
  out.before = live.success_probability(0, t);
  live.observe({"A_B", "A", "B", t, seconds(20), false, ""});
  const Time end = t + seconds(20);
  out.at_once = live.success_probability(0, end + seconds(30));
  out.after_10_minutes = live.success_probability(0, end + minutes(10));
  out.after_6_hours = live.success_probability(0, end + hours(6));
  return out;
}

TEST(LiveFailures, AClosureKeepsTheEstimateLowForHours) {
  const auto r = react(daily_failures(3.0));
  EXPECT_GT(r.before, 0.9);
  EXPECT_LT(r.at_once, 0.2);           // the current episode: the next try fails
  EXPECT_LT(r.after_10_minutes, 0.2);  // still closed 10 minutes later
  EXPECT_GT(r.after_6_hours, 0.8);     // the closure has ended
}

TEST(LiveFailures, APersonInTheWayIsForgottenAtOnce) {
  const auto r = react(daily_failures(0.0));
  EXPECT_GT(r.before, 0.9);
  EXPECT_GT(r.at_once, 0.8);  // the retry 30 s later succeeded every time in the log
  EXPECT_GT(r.after_10_minutes, 0.9);
}

TEST(LiveFailures, TheFailureIsSeenOnlyByItsEdge) {
  std::vector<Traversal> log = daily_failures(3.0);
  for (auto t : daily_failures(3.0)) {
    t.edge_id = "B_A";
    log.push_back(t);
  }
  const std::vector<EdgeSpec> edges = {{"A_B", 20}, {"B_A", 20}};
  auto models = *EdgeModels::fit(edges, log);
  LiveEdgeModels live(models);
  const Time t = monday() + hours(24 * 28 + 15);
  const double other_before = live.success_probability(1, t + minutes(1));
  live.observe({"A_B", "A", "B", t, seconds(20), false, ""});
  EXPECT_LT(live.success_probability(0, t + minutes(1)), 0.2);
  EXPECT_DOUBLE_EQ(live.success_probability(1, t + minutes(1)), other_before);
}

}  // namespace
}  // namespace rondo::learn
