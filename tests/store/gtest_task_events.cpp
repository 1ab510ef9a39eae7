#include "rondo/store/task_events.h"

#include <SQLiteCpp/Database.h>
#include <gtest/gtest.h>

#include "rondo/store/task_table.h"
#include "store/temp_db.h"

namespace rondo::store {
namespace {

using testing::TempDb;

Time at(int s) {
  return Time{seconds(s)};
}

class TaskEvents : public ::testing::Test {
 protected:
  void SetUp() override {
    auto opened = Store::open(tmp_.path());
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    db_.emplace(std::move(*opened));
    for (const char* id : {"t1", "t2"}) {
      ASSERT_TRUE(add_task(db(), {id, Json::object(), "queued", at(0), at(0)}).ok());
    }
  }
  Store& db() { return *db_; }

  TempDb tmp_;
  std::optional<Store> db_;
};

TEST_F(TaskEvents, AppendsInOrderWithIncreasingSequenceNumbers) {
  const auto before = read_task_events(db());
  ASSERT_TRUE(before.ok());
  ASSERT_EQ(before->size(), 2u);  // the two acceptances
  std::int64_t last = before->back().seq;
  // Times deliberately not monotonic: the log keeps the order of appends, not of times.
  const TaskEvent appended[] = {
      {0, at(50), "t1", "navigating", "scheduled"},
      {0, at(40), "t2", "waiting", "too early"},
      {0, at(60), "t1", "acting", ""},
  };
  for (const TaskEvent& e : appended) {
    auto seq = append_task_event(db(), e);
    ASSERT_TRUE(seq.ok()) << seq.error().message;
    EXPECT_GT(*seq, last);
    last = *seq;
  }
  auto all = read_task_events(db());
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 5u);
  for (std::size_t i = 0; i < 3; ++i) {
    TaskEvent expected = appended[i];
    expected.seq = (*all)[i + 2].seq;
    EXPECT_EQ((*all)[i + 2], expected);
  }
  for (std::size_t i = 1; i < all->size(); ++i) EXPECT_LT((*all)[i - 1].seq, (*all)[i].seq);
}

TEST_F(TaskEvents, ReadsAfterASequenceNumberAndPerTask) {
  auto first = append_task_event(db(), {0, at(1), "t1", "a", ""});
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(append_task_event(db(), {0, at(2), "t2", "b", ""}).ok());
  ASSERT_TRUE(append_task_event(db(), {0, at(3), "t1", "c", ""}).ok());

  auto newer = read_task_events(db(), *first);
  ASSERT_TRUE(newer.ok());
  ASSERT_EQ(newer->size(), 2u);
  EXPECT_EQ((*newer)[0].event, "b");
  EXPECT_EQ((*newer)[1].event, "c");

  auto of_t1 = read_task_events_of(db(), "t1");
  ASSERT_TRUE(of_t1.ok());
  std::vector<std::string> names;
  for (const auto& e : *of_t1) names.push_back(e.event);
  EXPECT_EQ(names, (std::vector<std::string>{"queued", "a", "c"}));
  EXPECT_TRUE(read_task_events_of(db(), "nobody")->empty());
}

TEST_F(TaskEvents, AnEventForAnUnknownTaskIsRefused) {
  auto seq = append_task_event(db(), {0, at(1), "ghost", "failed", ""});
  ASSERT_FALSE(seq.ok());
  EXPECT_EQ(seq.error().code, ErrorCode::kNotFound);
  EXPECT_NE(seq.error().message.find("ghost"), std::string::npos);
  EXPECT_EQ(read_task_events(db())->size(), 2u);
}

// There is no API to change the log; the schema refuses it too, whoever asks.
TEST_F(TaskEvents, TheDatabaseRefusesUpdatesAndDeletes) {
  SQLite::Database raw(tmp_.path(), SQLite::OPEN_READWRITE);
  for (const char* sql : {"UPDATE task_events SET reason = 'rewritten'", "DELETE FROM task_events",
                          "DELETE FROM task_events WHERE task_id = 't1'"}) {
    try {
      raw.exec(sql);
      ADD_FAILURE() << sql << " was allowed";
    } catch (const SQLite::Exception& e) {
      EXPECT_NE(std::string(e.what()).find("append-only"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(read_task_events(db())->size(), 2u);
}

TEST_F(TaskEvents, SurviveReopening) {
  ASSERT_TRUE(append_task_event(db(), {0, at(9), "t2", "dropped", "no schedule"}).ok());
  db_.reset();
  auto again = Store::open(tmp_.path(), {.mode = OpenMode::kMustExist});
  ASSERT_TRUE(again.ok());
  auto all = read_task_events(*again);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 3u);
  EXPECT_EQ(all->back().reason, "no schedule");
}

}  // namespace
}  // namespace rondo::store
