#include "rondo/store/events.h"

#include <gtest/gtest.h>

#include "rondo/store/task_table.h"
#include "store/store_backends.h"

namespace rondo::store {
namespace {


Time at(int s) {
  return Time{seconds(s)};
}

class Events : public testing::BackendTest {
 protected:
  void SetUp() override {
    BackendTest::SetUp();
    if (HasFatalFailure()) return;
    auto opened = temp().open();
    ASSERT_TRUE(opened.ok()) << opened.error().message;
    db_.emplace(std::move(*opened));
    for (const char* id : {"t1", "t2"}) {
      ASSERT_TRUE(add_task(db(), {id, Json::object(), "queued", at(0), at(0)}).ok());
    }
  }
  Store& db() { return *db_; }

  std::optional<Store> db_;
};

TEST_P(Events, AppendsInOrderWithIncreasingSequenceNumbers) {
  const auto before = read_events(db());
  ASSERT_TRUE(before.ok());
  ASSERT_EQ(before->size(), 2u);  // the two acceptances
  std::int64_t last = before->back().seq;
  // Times deliberately not monotonic: the log keeps the order of appends, not of times.
  const Event appended[] = {
      {.time = at(50), .task_id = "t1", .event = "navigating", .reason = "scheduled"},
      {.time = at(40), .task_id = "t2", .event = "waiting", .code = "early", .reason = "too early"},
      {.time = at(60), .subject = Subject::kRobot, .about = "r1", .event = "fault", .code = "robot fault"},
  };
  for (const Event& e : appended) {
    auto seq = append_event(db(), e);
    ASSERT_TRUE(seq.ok()) << seq.error().message;
    EXPECT_GT(*seq, last);
    last = *seq;
  }
  auto all = read_events(db());
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 5u);
  for (std::size_t i = 0; i < 3; ++i) {
    Event expected = appended[i];
    expected.seq = (*all)[i + 2].seq;
    if (expected.subject == Subject::kRobot) expected.robot = expected.about;  // a robot event is about its robot
    EXPECT_EQ((*all)[i + 2], expected);
  }
  for (std::size_t i = 1; i < all->size(); ++i) EXPECT_LT((*all)[i - 1].seq, (*all)[i].seq);
}

TEST_P(Events, ReadsAfterASequenceNumberAndPerTask) {
  auto first = append_event(db(), {.time = at(1), .task_id = "t1", .event = "a"});
  ASSERT_TRUE(first.ok());
  ASSERT_TRUE(append_event(db(), {.time = at(2), .task_id = "t2", .event = "b"}).ok());
  ASSERT_TRUE(append_event(db(), {.time = at(3), .task_id = "t1", .event = "c"}).ok());

  auto newer = read_events(db(), *first);
  ASSERT_TRUE(newer.ok());
  ASSERT_EQ(newer->size(), 2u);
  EXPECT_EQ((*newer)[0].event, "b");
  EXPECT_EQ((*newer)[1].event, "c");

  auto of_t1 = read_events_of(db(), "t1");
  ASSERT_TRUE(of_t1.ok());
  std::vector<std::string> names;
  for (const auto& e : *of_t1) names.push_back(e.event);
  EXPECT_EQ(names, (std::vector<std::string>{"queued", "a", "c"}));
  EXPECT_TRUE(read_events_of(db(), "nobody")->empty());
}

TEST_P(Events, AnEventForAnUnknownTaskIsRefused) {
  auto seq = append_event(db(), {.time = at(1), .task_id = "ghost", .event = "failed"});
  ASSERT_FALSE(seq.ok());
  EXPECT_EQ(seq.error().code, ErrorCode::kNotFound);
  EXPECT_NE(seq.error().message.find("ghost"), std::string::npos);
  EXPECT_EQ(read_events(db())->size(), 2u);
}

TEST_P(Events, ATaskEventNamesItsTaskAndNoOtherEventDoes) {
  EXPECT_EQ(append_event(db(), {.time = at(1), .event = "x"}).error().code, ErrorCode::kInvalidInput);
  EXPECT_EQ(append_event(db(), {.time = at(1), .subject = Subject::kSchedule, .task_id = "t1", .event = "x"})
                .error()
                .code,
            ErrorCode::kInvalidInput);
  ASSERT_TRUE(append_event(db(), {.time = at(5), .subject = Subject::kRequest, .about = "req-3", .event = "rejected",
                                  .code = "invalid request", .reason = "no node 'Cellar'"})
                  .ok());
  const auto end = log_end(db());
  ASSERT_TRUE(end.ok());
  EXPECT_EQ(end->time, at(5));
  const auto last = read_events(db(), end->seq - 1);
  ASSERT_EQ(last->size(), 1u);
  EXPECT_EQ(last->front().subject, Subject::kRequest);
  EXPECT_EQ(last->front().about, "req-3");
  EXPECT_TRUE(last->front().task_id.empty());
  EXPECT_EQ(read_events(db(), 0, 1)->size(), 1u);  // a limit
  EXPECT_EQ(parse_subject("robot").value(), Subject::kRobot);
  // The executive process itself: a takeover names the instance that became active.
  const auto taken = append_event(db(), {.time = at(6),
                                         .subject = Subject::kExecutive,
                                         .about = "rondo-serve-4711",
                                         .event = "takeover",
                                         .code = "takeover"});
  ASSERT_TRUE(taken.ok()) << taken.error().message;
  const auto takeover = read_events(db(), *taken - 1);
  ASSERT_EQ(takeover->size(), 1u);
  EXPECT_EQ(takeover->front().subject, Subject::kExecutive);
  EXPECT_EQ(takeover->front().about, "rondo-serve-4711");
  EXPECT_EQ(parse_subject("executive").value(), Subject::kExecutive);
  EXPECT_EQ(to_string(Subject::kExecutive), std::string("executive"));
  EXPECT_FALSE(parse_subject("moon").ok());
}

// There is no API to change the log; the schema refuses it too, whoever asks.
TEST_P(Events, TheDatabaseRefusesUpdatesAndDeletes) {
  std::vector<std::string> refused = {"UPDATE events SET reason = 'rewritten'", "DELETE FROM events",
                                      "DELETE FROM events WHERE task_id = 't1'"};
  if (postgres()) refused.emplace_back("TRUNCATE events CASCADE");  // which no row trigger sees
  for (const std::string& sql : refused) {
    const std::string error = temp().raw_sql(sql);
    EXPECT_NE(error.find("append-only"), std::string::npos) << sql << ": " << (error.empty() ? "allowed" : error);
  }
  EXPECT_EQ(read_events(db())->size(), 2u);
  EXPECT_EQ(temp().raw_sql("INSERT INTO events (time_ms, subject, event) VALUES (1, 'schedule', 'appended')"), "");
}

TEST_P(Events, SurviveReopening) {
  ASSERT_TRUE(append_event(db(), {.time = at(9), .task_id = "t2", .event = "dropped", .reason = "no schedule"}).ok());
  db_.reset();
  auto again = temp().open({.mode = OpenMode::kMustExist});
  ASSERT_TRUE(again.ok());
  auto all = read_events(*again);
  ASSERT_TRUE(all.ok());
  ASSERT_EQ(all->size(), 3u);
  EXPECT_EQ(all->back().reason, "no schedule");
}

RONDO_ON_BOTH_BACKENDS(Events);

}  // namespace
}  // namespace rondo::store
