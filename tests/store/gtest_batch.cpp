// store::Batch: writes made while it is open are committed together, each write stays all or
// nothing on its own inside it, and a batch not committed leaves nothing.
#include "rondo/store/batch.h"

#include <gtest/gtest.h>

#include "rondo/store/task_table.h"
#include "store/store_backends.h"

namespace rondo::store {
namespace {


TaskRow row(const std::string& id) {
  return TaskRow{
      .id = id, .task = Json{{"id", id}}, .state = "queued", .created = Time{seconds(1)}, .updated = Time{seconds(1)}};
}

class BatchTest : public testing::BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (HasFatalFailure()) return;
    auto opened = temp().open();
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    db_.emplace(std::move(*opened));
    auto other = temp().open({.mode = OpenMode::kMustExist});
    ASSERT_TRUE(other.ok());
    reader_.emplace(std::move(*other));
  }
  bool seen(const std::string& id) { return get_task(*reader_, id).ok(); }

  std::optional<Store> db_, reader_;
};

TEST_P(BatchTest, WritesBecomeVisibleTogetherAtTheCommit) {
  Batch batch(*db_);
  ASSERT_TRUE(add_task(*db_, row("a")).ok());
  ASSERT_TRUE(set_task_state(*db_, "a", "navigating", Time{seconds(2)}, "departed").ok());
  ASSERT_TRUE(add_task(*db_, row("b")).ok());
  EXPECT_TRUE(get_task(*db_, "a").ok());  // the writer reads its own writes
  EXPECT_FALSE(seen("a"));
  EXPECT_FALSE(seen("b"));
  ASSERT_TRUE(batch.commit().ok());
  ASSERT_TRUE(seen("a"));
  EXPECT_EQ(get_task(*reader_, "a")->state, "navigating");
  EXPECT_TRUE(seen("b"));
}

TEST_P(BatchTest, AWriteThatFailsInsideIsUndoneAloneAndTheRestIsKept) {
  ASSERT_TRUE(add_task(*db_, row("a")).ok());
  Batch batch(*db_);
  const std::vector<TaskRow> rows{row("b"), row("a")};  // "a" is taken: the whole add is refused
  EXPECT_EQ(add_tasks(*db_, rows).error().code, ErrorCode::kInvalidInput);
  ASSERT_TRUE(add_task(*db_, row("c")).ok());
  ASSERT_TRUE(batch.commit().ok());
  EXPECT_FALSE(seen("b"));
  EXPECT_TRUE(seen("c"));
}

TEST_P(BatchTest, ABatchNotCommittedLeavesNothingAndABatchInsideABatchJoinsIt) {
  {
    Batch batch(*db_);
    ASSERT_TRUE(add_task(*db_, row("a")).ok());
  }
  EXPECT_FALSE(get_task(*db_, "a").ok());
  Batch outer(*db_);
  {
    Batch inner(*db_);
    ASSERT_TRUE(add_task(*db_, row("b")).ok());
    ASSERT_TRUE(inner.commit().ok());
  }
  EXPECT_FALSE(seen("b"));  // the outer batch is still open
  ASSERT_TRUE(outer.commit().ok());
  EXPECT_TRUE(seen("b"));
}

RONDO_ON_BOTH_BACKENDS(BatchTest);

}  // namespace
}  // namespace rondo::store
