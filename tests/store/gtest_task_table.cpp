#include "rondo/store/task_table.h"

#include <gtest/gtest.h>

#include "rondo/store/events.h"
#include "store/child_process.h"
#include "store/store_backends.h"

namespace rondo::store {
namespace {

using testing::run_in_child;

Time at(int s) {
  return Time{seconds(s)};
}

TaskRow sample(std::string id, int created_s = 100) {
  Json task = Json::parse(R"({
    "id": "ID", "name": "check the fire extinguisher", "kind": "standard",
    "window": {"release": "2014-09-02T08:00:00Z", "deadline": "2014-09-02T11:45:00Z"},
    "duration": "2m", "priority": 3, "start": "WayPoint3", "interruptible": true,
    "actions": [{"name": "look", "args": {"at": "extinguisher 2", "zoom": 1.5}}],
    "note": "caf\u00e9 \u2013 2nd floor"
  })");
  task["id"] = id;
  return TaskRow{std::move(id), std::move(task), "queued", at(created_s), at(created_s)};
}

class TaskTable : public testing::BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (HasFatalFailure()) return;
    auto opened = temp().open();
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    db_.emplace(std::move(*opened));
  }
  Store& db() { return *db_; }

  std::optional<Store> db_;
};

class TaskTableDurability : public testing::BackendTest {};

TEST_P(TaskTable, RoundTripsEveryField) {
  const TaskRow r = sample("t1");
  ASSERT_TRUE(add_task(db(), r).ok());
  auto back = get_task(db(), "t1");
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(*back, r);
  EXPECT_EQ(back->task.dump(), r.task.dump());  // key order is kept too
}

TEST_P(TaskTable, AnAcceptedTaskIsVisibleToAnotherConnectionAtOnce) {
  auto other = temp().open({.mode = OpenMode::kMustExist});
  ASSERT_TRUE(other.ok());
  EXPECT_EQ(get_task(*other, "t1").error().code, ErrorCode::kNotFound);
  ASSERT_TRUE(add_task(db(), sample("t1")).ok());
  auto seen = get_task(*other, "t1");
  ASSERT_TRUE(seen.ok()) << seen.error().message;
  EXPECT_EQ(seen->state, "queued");
}

TEST_P(TaskTable, AddingWritesTheAcceptanceEvent) {
  ASSERT_TRUE(add_task(db(), sample("t1", 42), "from the web page").ok());
  auto events = read_events_of(db(), "t1");
  ASSERT_TRUE(events.ok());
  ASSERT_EQ(events->size(), 1u);
  EXPECT_EQ((*events)[0].time, at(42));
  EXPECT_EQ((*events)[0].event, "queued");
  EXPECT_EQ((*events)[0].reason, "from the web page");
}

TEST_P(TaskTable, RefusesADuplicateIdAndKeepsTheFirst) {
  ASSERT_TRUE(add_task(db(), sample("t1")).ok());
  TaskRow second = sample("t1", 200);
  second.state = "dropped";
  Status s = add_task(db(), second);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(s.error().message.find("'t1' is already stored"), std::string::npos) << s.error().message;
  EXPECT_EQ(get_task(db(), "t1")->state, "queued");
  EXPECT_EQ(read_events_of(db(), "t1")->size(), 1u);  // no event for the refused one
}

TEST_P(TaskTable, StoresABatchWhole) {
  const std::vector<TaskRow> batch{sample("a", 10), sample("b", 10), sample("c", 10)};
  ASSERT_TRUE(add_tasks(db(), batch, "routine").ok());
  auto all = list_tasks(db());
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(*all, batch);
  for (const auto& t : batch) {
    auto events = read_events_of(db(), t.id);
    ASSERT_EQ(events->size(), 1u);
    EXPECT_EQ((*events)[0].reason, "routine");
  }
}

TEST_P(TaskTable, StoresNoneOfABatchWithAStoredId) {
  ASSERT_TRUE(add_task(db(), sample("b")).ok());
  const std::vector<TaskRow> batch{sample("a", 200), sample("b", 200), sample("c", 200)};
  Status s = add_tasks(db(), batch);
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(s.error().message.find("'b' is already stored"), std::string::npos) << s.error().message;
  auto all = list_tasks(db());
  ASSERT_EQ(all->size(), 1u);  // "a", before the refused one, was rolled back too
  EXPECT_EQ((*all)[0], sample("b"));
  EXPECT_TRUE(read_events_of(db(), "a")->empty());
  EXPECT_EQ(read_events_of(db(), "b")->size(), 1u);
}

TEST_P(TaskTable, AnEmptyBatchStoresNothing) {
  ASSERT_TRUE(add_tasks(db(), {}).ok());
  EXPECT_TRUE(list_tasks(db())->empty());
}

TEST_P(TaskTable, StoresNoneOfABatchThatRepeatsAnId) {
  Status s = add_tasks(db(), std::vector<TaskRow>{sample("a"), sample("a", 300)});
  ASSERT_FALSE(s.ok());
  EXPECT_TRUE(list_tasks(db())->empty());
}

TEST_P(TaskTable, RefusesAnEmptyId) {
  Status s = add_task(db(), sample(""));
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::kInvalidInput);
}

TEST_P(TaskTable, StateChangesUpdateTheTaskAndAppendEvents) {
  ASSERT_TRUE(add_task(db(), sample("t1", 100)).ok());
  ASSERT_TRUE(set_task_state(db(), "t1", "navigating", at(150), "scheduled start").ok());
  ASSERT_TRUE(set_task_state(db(), "t1", "failed", at(180), "door A-110 closed").ok());
  auto r = get_task(db(), "t1");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->state, "failed");
  EXPECT_EQ(r->created, at(100));
  EXPECT_EQ(r->updated, at(180));
  auto events = read_events_of(db(), "t1");
  ASSERT_TRUE(events.ok());
  ASSERT_EQ(events->size(), 3u);
  EXPECT_EQ((*events)[1].event, "navigating");
  EXPECT_EQ((*events)[2].event, "failed");
  EXPECT_EQ((*events)[2].reason, "door A-110 closed");
  EXPECT_EQ((*events)[2].time, at(180));
}

// The planned start and end go with a state change when given (both may be none), and stay as
// they are when not.
TEST_P(TaskTable, AStateChangeRecordsThePlannedTimesWhenGiven) {
  ASSERT_TRUE(add_task(db(), sample("t1", 100)).ok());
  EXPECT_FALSE(get_task(db(), "t1")->planned_start.has_value());
  ASSERT_TRUE(set_task_state(db(), "t1", "navigating", at(150), "", "", PlannedTimes{at(160), at(280)}).ok());
  ASSERT_TRUE(set_task_state(db(), "t1", "acting", at(170), "").ok());
  auto r = get_task(db(), "t1");
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->planned_start, at(160));
  EXPECT_EQ(r->planned_end, at(280));
  ASSERT_TRUE(set_task_state(db(), "t1", "cancelled", at(180), "", "", PlannedTimes{}).ok());
  r = get_task(db(), "t1");
  EXPECT_FALSE(r->planned_start.has_value());
  EXPECT_FALSE(r->planned_end.has_value());
}

TEST_P(TaskTable, StateChangeOfAnUnknownTaskIsNotFoundAndLogsNothing) {
  Status s = set_task_state(db(), "ghost", "failed", at(1), "");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.error().code, ErrorCode::kNotFound);
  EXPECT_TRUE(read_events(db())->empty());
}

TEST_P(TaskTable, GetOfAnUnknownTaskIsNotFound) {
  auto r = get_task(db(), "ghost");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().code, ErrorCode::kNotFound);
  EXPECT_NE(r.error().message.find("ghost"), std::string::npos);
}

TEST_P(TaskTable, ListsInAcceptanceOrderAndByState) {
  ASSERT_TRUE(add_task(db(), sample("b", 20)).ok());
  ASSERT_TRUE(add_task(db(), sample("c", 10)).ok());
  ASSERT_TRUE(add_task(db(), sample("a", 20)).ok());
  ASSERT_TRUE(set_task_state(db(), "b", "succeeded", at(30), "").ok());

  auto all = list_tasks(db());
  ASSERT_TRUE(all.ok());
  std::vector<std::string> ids;
  for (const auto& r : *all) ids.push_back(r.id);
  EXPECT_EQ(ids, (std::vector<std::string>{"c", "a", "b"}));

  auto queued = list_tasks_in_state(db(), "queued");
  ASSERT_TRUE(queued.ok());
  ASSERT_EQ(queued->size(), 2u);
  EXPECT_EQ((*queued)[0].id, "c");
  EXPECT_EQ((*queued)[1].id, "a");
  EXPECT_TRUE(list_tasks_in_state(db(), "preempted")->empty());
}

// The acceptance promise: once add_task returns, the task is on disk. The child process adds a
// task and is killed at once, without closing the connection; the task is still there after.
TEST_P(TaskTableDurability, AnAcceptedTaskSurvivesTheProcessDyingRightAfter) {
  ASSERT_TRUE(temp().open().ok());
  auto end = run_in_child([&] {
    auto db = temp().open();
    if (!db || !add_task(*db, sample("survivor"))) ::_exit(4);
    ::raise(SIGKILL);
  });
  ASSERT_TRUE(end.killed_by(SIGKILL)) << "child status " << end.status;

  auto db = temp().open({.mode = OpenMode::kMustExist});
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto r = get_task(*db, "survivor");
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(*r, sample("survivor"));
  EXPECT_EQ(read_events_of(*db, "survivor")->size(), 1u);
}

TEST_P(TaskTableDurability, SurvivesAnExitWithoutClosing) {
  auto end = run_in_child([&] {
    auto db = temp().open();
    if (!db || !add_task(*db, sample("t1"))) ::_exit(4);
    ::_exit(0);  // no destructor: the connection is never closed, the WAL never checkpointed
  });
  ASSERT_TRUE(end.exited_with(0)) << "child status " << end.status;
  auto db = temp().open({.mode = OpenMode::kMustExist});
  ASSERT_TRUE(db.ok()) << db.error().message;
  EXPECT_TRUE(get_task(*db, "t1").ok());
}

RONDO_ON_BOTH_BACKENDS(TaskTable);
RONDO_ON_BOTH_BACKENDS(TaskTableDurability);

}  // namespace
}  // namespace rondo::store
