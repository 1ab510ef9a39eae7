// The request queue (store/requests.h): queued in order, taken exactly once, taken in the same
// transaction as the tasks it adds (a refused batch leaves it waiting), and with its event and
// the meta entries that keep what it added (routines).
#include <gtest/gtest.h>

#include "rondo/store/events.h"
#include "rondo/store/requests.h"
#include "rondo/store/robot_state.h"
#include "rondo/store/task_table.h"
#include "store/store_backends.h"

namespace rondo::store {
namespace {


const Time kT0 = Time{Duration{1'795'392'000'000}};

RequestRow request(const std::string& sentence) {
  return {.queued = kT0, .source = "words", .sentence = sentence, .body = Json{{"tasks", Json::array()}}};
}

TaskRow row(const std::string& id) {
  return {.id = id, .task = Json{{"id", id}}, .state = "queued", .created = kT0, .updated = kT0};
}

class Requests : public testing::BackendTest {};

TEST_P(Requests, QueuedInOrderAndTakenOnce) {
  auto db = temp().open();
  ASSERT_TRUE(db.ok());
  EXPECT_EQ(*queue_request(*db, request("a")), 1);
  EXPECT_EQ(*queue_request(*db, request("b")), 2);
  EXPECT_EQ(queue_request(*db, {.body = Json::array()}).error().code, ErrorCode::kInvalidInput);
  ASSERT_EQ(waiting_requests(*db)->size(), 2u);
  const Event e{.time = kT0, .subject = Subject::kRequest, .about = "request 1", .event = "rejected"};
  ASSERT_TRUE(take_request(*db, {1, kT0, "rejected: no"}, &e).ok());
  EXPECT_EQ(take_request(*db, {1, kT0, "again"}).error().code, ErrorCode::kConflict);
  EXPECT_EQ(take_request(*db, {9, kT0, "x"}).error().code, ErrorCode::kNotFound);
  const auto waiting = waiting_requests(*db);
  ASSERT_EQ(waiting->size(), 1u);
  EXPECT_EQ(waiting->front().sentence, "b");
  const auto all = list_requests(*db);
  EXPECT_EQ((*all)[0].outcome, "rejected: no");
  EXPECT_EQ((*all)[0].taken, kT0);
  EXPECT_EQ(read_events(*db)->size(), 1u);  // the event, once
}

TEST_P(Requests, TakenInTheTransactionThatStoresItsTasks) {
  auto db = temp().open();
  ASSERT_TRUE(db.ok());
  ASSERT_TRUE(add_task(*db, row("t0")).ok());
  ASSERT_TRUE(queue_request(*db, request("two tasks")).ok());
  // A batch the store refuses (t0 is stored already) leaves the request waiting.
  const RequestTaken taken{1, kT0, "added 2 task(s)"};
  const std::vector<TaskRow> refused = {row("t1"), row("t0")};
  EXPECT_FALSE(add_tasks(*db, refused, "added", "added", &taken).ok());
  EXPECT_EQ(waiting_requests(*db)->size(), 1u);
  EXPECT_FALSE(get_task(*db, "t1").ok());
  const std::vector<TaskRow> good = {row("t1"), row("t2")};
  ASSERT_TRUE(add_tasks(*db, good, "added", "added", &taken).ok());
  EXPECT_TRUE(waiting_requests(*db)->empty());
  EXPECT_TRUE(get_task(*db, "t2").ok());
  // Taken already: the tasks are not stored a second time.
  const std::vector<TaskRow> again = {row("t3")};
  EXPECT_EQ(add_tasks(*db, again, "added", "added", &taken).error().code, ErrorCode::kConflict);
  EXPECT_FALSE(get_task(*db, "t3").ok());
}

TEST_P(Requests, TakenWithItsMetaEntriesInOneTransaction) {
  auto db = temp().open();
  ASSERT_TRUE(db.ok());
  ASSERT_TRUE(queue_request(*db, request("a routine")).ok());
  const Event e{.time = kT0, .subject = Subject::kRequest, .about = "request 1", .event = "routines added"};
  ASSERT_TRUE(take_request(*db, {1, kT0, "added 1 routine(s)", {{"k", "first"}}}, &e).ok());
  EXPECT_EQ(get_meta(*db, "k")->value_or(""), "first");
  // Taken already: neither the meta entry nor the event is written again.
  EXPECT_EQ(take_request(*db, {1, kT0, "again", {{"k", "second"}}}, &e).error().code, ErrorCode::kConflict);
  EXPECT_EQ(get_meta(*db, "k")->value_or(""), "first");
  EXPECT_EQ(read_events(*db)->size(), 1u);
  EXPECT_EQ(list_requests(*db)->front().outcome, "added 1 routine(s)");
}

RONDO_ON_BOTH_BACKENDS(Requests);

}  // namespace
}  // namespace rondo::store
