// store::read_back: what a restarting executive reads from its store.
#include "rondo/store/read_back.h"

#include <gtest/gtest.h>

#include "rondo/store/traversal_log.h"
#include "store/store_backends.h"

namespace rondo::store {
namespace {


Time at(int s) {
  return Time{seconds(s)};
}

TaskRow row(const std::string& id, int created_s) {
  return {.id = id,
          .task = Json{{"id", id}},
          .state = "queued",
          .created = at(created_s),
          .updated = at(created_s),
          .source = "test"};
}

void note(Store& db, const std::string& id, int s, const std::string& event, const std::string& code,
          const std::string& reason = "") {
  ASSERT_TRUE(append_event(db, {.time = at(s), .task_id = id, .event = event, .code = code, .reason = reason}));
}

class ReadBack : public testing::BackendTest {};
class ReadBackMeta : public testing::BackendTest {};

TEST_P(ReadBack, AnEmptyStoreHasNothing) {
  auto db = temp().open().value();
  const StoredRun run = read_back(db, "robot").value();
  EXPECT_TRUE(run.tasks.empty());
  EXPECT_TRUE(run.events.empty());
  EXPECT_EQ(run.log_end.seq, 0);
  EXPECT_FALSE(run.traversals_end);
  EXPECT_FALSE(run.robot);
  EXPECT_FALSE(run.latest());
}

TEST_P(ReadBack, EachTaskComesWithTheChangeThatPutItInItsStateAndItsDropForNow) {
  {
    auto db = temp().open().value();
    // One batch whose ids are not in alphabetical order: the read-back keeps the order accepted.
    const std::vector<TaskRow> batch{row("zeta", 10), row("alpha", 10), row("mid", 10), row("gone", 10)};
    ASSERT_TRUE(add_tasks(db, batch, "added by test", "added"));
    // zeta: ran, was preempted back to the queue, then dropped for now.
    ASSERT_TRUE(set_task_state(db, "zeta", "navigating", at(20), "to Office", "departed"));
    ASSERT_TRUE(
        set_task_state(db, "zeta", "queued", at(30), "preempted by X; back in the queue", "preempted on demand"));
    note(db, "zeta", 30, "dropped for now", "does not fit", "no room before 10:00");
    // alpha: dropped for now, then offered again and scheduled: no longer dropped.
    note(db, "alpha", 11, "dropped for now", "dropped lowest priority", "lowest");
    note(db, "alpha", 40, "re-offered", "scheduled", "fits again");
    // mid: dropped for now, then it left the queue (a change of state ends the drop).
    note(db, "mid", 12, "dropped for now", "does not fit", "x");
    ASSERT_TRUE(set_task_state(db, "mid", "navigating", at(50), "to Lab", "departed"));
    // gone: dropped for good.
    note(db, "gone", 13, "dropped for now", "does not fit", "y");
    ASSERT_TRUE(set_task_state(db, "gone", "dropped", at(60), "y", "does not fit"));
    ASSERT_TRUE(set_task_progress(db, "mid", Json{{"actions_done", 1}}));
    ASSERT_TRUE(add_traversal(
        db, {.edge_id = "A_B", .from = "A", .to = "B", .start = at(70), .duration = seconds(15), .success = true}));
    ASSERT_TRUE(save_robot_state(db, {.robot = "robot", .node = "B", .updated = at(80)}));
    ASSERT_TRUE(set_meta(db, {{"run.seed", "7"}, {"run.days", "3"}}));
  }
  auto db = temp().open({.mode = OpenMode::kReadOnly}).value();
  const StoredRun run = read_back(db, "robot").value();
  ASSERT_EQ(run.tasks.size(), 4u);
  EXPECT_EQ(run.tasks[0].row.id, "zeta");
  EXPECT_EQ(run.tasks[1].row.id, "alpha");
  EXPECT_EQ(run.tasks[2].row.id, "mid");
  EXPECT_EQ(run.tasks[3].row.id, "gone");
  for (const StoredTask& t : run.tasks) {
    EXPECT_EQ(t.added_events, 1) << t.row.id;
    EXPECT_EQ(t.row.source, "test");
    EXPECT_EQ(t.row.created, at(10));
    ASSERT_TRUE(t.last_transition) << t.row.id;
  }
  const StoredTask& zeta = run.tasks[0];
  EXPECT_EQ(zeta.row.state, "queued");
  EXPECT_EQ(zeta.last_transition->code, "preempted on demand");
  EXPECT_EQ(zeta.last_transition->reason, "preempted by X; back in the queue");
  ASSERT_TRUE(zeta.dropped_for_now);
  EXPECT_EQ(zeta.dropped_for_now->code, "does not fit");
  EXPECT_EQ(zeta.dropped_for_now->reason, "no room before 10:00");

  const StoredTask& alpha = run.tasks[1];
  EXPECT_EQ(alpha.last_transition->code, "added");
  EXPECT_FALSE(alpha.dropped_for_now);

  const StoredTask& mid = run.tasks[2];
  EXPECT_EQ(mid.row.state, "navigating");
  EXPECT_EQ(mid.last_transition->time, at(50));
  EXPECT_FALSE(mid.dropped_for_now);
  EXPECT_EQ(mid.row.progress, (Json{{"actions_done", 1}}));

  const StoredTask& gone = run.tasks[3];
  EXPECT_EQ(gone.row.state, "dropped");
  EXPECT_EQ(gone.last_transition->reason, "y");
  EXPECT_FALSE(gone.dropped_for_now);

  EXPECT_EQ(run.events.size(), 13u);  // 4 added, 3 + 2 + 2 + 2 later
  EXPECT_EQ(run.log_end.seq, run.events.back().seq);
  EXPECT_EQ(run.log_end.time, at(60));
  EXPECT_EQ(run.traversals_end, at(85));
  ASSERT_TRUE(run.robot);
  EXPECT_EQ(run.robot->node, "B");
  EXPECT_EQ(run.meta, (std::map<std::string, std::string>{{"run.days", "3"}, {"run.seed", "7"}}));
  // The latest of the event log (60 s), the traversal log (85 s) and the robot's state (80 s).
  EXPECT_EQ(run.latest(), at(85));
}

TEST_P(ReadBack, TheLatestTimeIsTheRobotStateWhenItIsNewest) {
  auto db = temp().open().value();
  ASSERT_TRUE(add_task(db, row("t", 5), "added", "added"));
  ASSERT_TRUE(save_robot_state(db, {.robot = "robot", .node = "B", .updated = at(90)}));
  ASSERT_TRUE(save_robot_state(db, {.robot = "other", .node = "C", .updated = at(200)}));
  const StoredRun run = read_back(db, "robot").value();
  EXPECT_EQ(run.latest(), at(90));  // another robot's row is not this run's
}

TEST_P(ReadBackMeta, SeveralKeysAreSetInOneTransactionAndReadBackTogether) {
  auto db = temp().open().value();
  ASSERT_TRUE(set_meta(db, {{"a", "1"}, {"b", "2"}}));
  ASSERT_TRUE(set_meta(db, {{"b", "3"}}));
  EXPECT_EQ(read_meta(db).value(), (std::map<std::string, std::string>{{"a", "1"}, {"b", "3"}}));
  EXPECT_EQ(get_meta(db, "b").value(), "3");
}

RONDO_ON_BOTH_BACKENDS(ReadBack);
RONDO_ON_BOTH_BACKENDS(ReadBackMeta);

}  // namespace
}  // namespace rondo::store
