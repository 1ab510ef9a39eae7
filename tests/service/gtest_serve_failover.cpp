// Two `rondo serve` processes on one PostgreSQL store (the test binary's throwaway cluster,
// tests/store/pg_cluster.h): one active, one standby. The active killed with SIGKILL: the standby
// takes the lease at the next epoch, restores the executive and serves every task the first one
// accepted. The active frozen with SIGSTOP until the standby has taken over, then resumed: it
// writes nothing more and commands nothing, and steps down. Every wait is for a condition, with a
// generous deadline.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <libpq-fe.h>

#include <chrono>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "live_service.h"
#include "serve_process.h"
#include "store/pg_cluster.h"
#include "test_files.h"

namespace rondo::test {
namespace {

const std::regex kActiveAt(R"(on http://127\.0\.0\.1:(\d+)/ \(speed)");
const std::regex kStandbyAt(R"(standby on http://127\.0\.0\.1:(\d+)/)");

// The rows of a query, as text; fails the test on an error.
std::vector<std::vector<std::string>> rows_of(const std::string& url, const std::string& sql) {
  std::vector<std::vector<std::string>> out;
  PGconn* conn = PQconnectdb(url.c_str());
  PGresult* r = PQexec(conn, sql.c_str());
  if (PQresultStatus(r) != PGRES_TUPLES_OK) {
    ADD_FAILURE() << sql << ": " << PQresultErrorMessage(r) << PQerrorMessage(conn);
  } else {
    for (int i = 0; i < PQntuples(r); ++i) {
      std::vector<std::string>& row = out.emplace_back();
      for (int j = 0; j < PQnfields(r); ++j) row.emplace_back(PQgetvalue(r, i, j));
    }
  }
  PQclear(r);
  PQfinish(conn);
  return out;
}

std::string one_value(const std::string& url, const std::string& sql) {
  const auto rows = rows_of(url, sql);
  return rows.empty() || rows[0].empty() ? "" : rows[0][0];
}

Child spawn_on(const std::string& url, const std::filesystem::path& data) {
  return spawn({RONDO_BINARY, "serve", "--listen", "127.0.0.1:0", "--data", data.string(), "--store", url, "--speed",
                "10"});
}

// Tasks to run now (so that the executive dispatches one soon after a takeover).
std::string tasks_body(const std::string& prefix, int n) {
  const Time now = std::chrono::time_point_cast<Duration>(std::chrono::system_clock::now());
  std::string tasks;
  const char* nodes[] = {"WayPoint2", "WayPoint5", "WayPoint10"};
  for (int i = 0; i < n; ++i)
    tasks += fmt::format(R"({}{{"id": "{}-{}", "window": {{"release": "{}", "deadline": "{}"}}, "duration": 30,
        "start_node": "{}"}})",
                         i ? "," : "", prefix, i, format_time(now), format_time(now + hours(2)), nodes[i % 3]);
  return R"({"tasks": [)" + tasks + "]}";
}

class ServeFailoverPostgres : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      url_ = store::testing::PgCluster::get().create_database();
    } catch (const std::exception& e) {
      FAIL() << e.what();
    }
    dir_ = fresh_dir("rondo-service-test", ::testing::UnitTest::GetInstance()->current_test_info()->name());
  }
  // The active (started first) and the standby, each with its port.
  void start_pair() {
    active_.emplace(spawn_on(url_, dir_ / "a"));
    active_port_ = active_->wait_for(kActiveAt);
    ASSERT_FALSE(active_port_.empty()) << active_->seen;
    standby_.emplace(spawn_on(url_, dir_ / "b"));
    standby_port_ = standby_->wait_for(kStandbyAt);
    ASSERT_FALSE(standby_port_.empty()) << standby_->seen;
  }
  // Every event in sequence order carries an epoch no lower than the one before it: no write of
  // an old active came after the new one's first.
  void expect_epochs_in_order() {
    const auto rows = rows_of(url_, "SELECT seq, epoch FROM events WHERE epoch > 0 ORDER BY seq");
    long long last = 0;
    for (const auto& r : rows) {
      const long long epoch = std::stoll(r[1]);
      EXPECT_GE(epoch, last) << "event " << r[0] << " written at epoch " << epoch << " after epoch " << last;
      last = std::max(last, epoch);
    }
  }

  std::string url_;
  std::filesystem::path dir_;
  std::optional<Child> active_, standby_;
  std::string active_port_, standby_port_;
};

TEST_F(ServeFailoverPostgres, TheStandbyTakesOverWhenTheActiveIsKilled) {
  start_pair();
  httplib::Client standby("127.0.0.1", std::stoi(standby_port_));
  standby.set_read_timeout(std::chrono::seconds(60));
  const auto health = standby.Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(body_of(health)["status"], "standby");
  EXPECT_EQ(body_of(health)["epoch"], 1);
  const auto refused = standby.Post("/api/v1/tasks", tasks_body("refused", 1), "application/json");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 503);
  EXPECT_EQ(refused->get_header_value("Retry-After"), "1");
  EXPECT_NE(standby.Get("/metrics")->body.find("rondo_role 0"), std::string::npos);

  httplib::Client active("127.0.0.1", std::stoi(active_port_));
  active.set_read_timeout(std::chrono::seconds(60));
  std::vector<std::string> accepted;
  for (int batch = 0; batch < 5; ++batch) {
    const auto r = active.Post("/api/v1/tasks", tasks_body(fmt::format("b{}", batch), 2), "application/json");
    ASSERT_TRUE(r);
    ASSERT_EQ(r->status, 201) << r->body;
    accepted.push_back(fmt::format("b{}-0", batch));
    accepted.push_back(fmt::format("b{}-1", batch));
  }
  ASSERT_EQ(::kill(active_->pid, SIGKILL), 0);
  EXPECT_EQ(active_->wait_exit(), 128 + SIGKILL);

  // The standby takes the lease at epoch 2 and serves on its own port.
  EXPECT_FALSE(standby_->wait_for(std::regex(R"(is the active executive at epoch (2))")).empty()) << standby_->seen;
  EXPECT_FALSE(standby_->wait_for(kActiveAt).empty()) << standby_->seen;
  ASSERT_TRUE(eventually([&] {
    const auto h = standby.Get("/healthz");
    return h && h->status == 200 && body_of(h)["status"] == "ok";
  }, seconds(60)));
  EXPECT_EQ(body_of(standby.Get("/healthz"))["epoch"], 2);
  EXPECT_NE(standby.Get("/metrics")->body.find("rondo_role 1"), std::string::npos);
  for (const std::string& id : accepted) {
    const auto t = standby.Get("/api/v1/tasks/" + id);
    ASSERT_TRUE(t);
    EXPECT_EQ(t->status, 200) << id << " was accepted by the killed active";
  }
  // It dispatches a task (the robot is commanded), and records the takeover with its epoch.
  EXPECT_FALSE(standby_->wait_for(std::regex(R"(epoch 2: (first task step sent) to the robot)"), std::chrono::seconds(120))
                   .empty())
      << standby_->seen;
  EXPECT_EQ(one_value(url_, "SELECT COUNT(*) FROM events WHERE event = 'takeover' AND epoch = 2"), "1");
  // About the executive process, named after the new holder, the one the lease row names.
  EXPECT_EQ(one_value(url_, "SELECT subject FROM events WHERE event = 'takeover' AND epoch = 2"), "executive");
  EXPECT_EQ(one_value(url_, "SELECT about FROM events WHERE event = 'takeover' AND epoch = 2"),
            one_value(url_, "SELECT holder FROM lease"));
  EXPECT_EQ(one_value(url_, "SELECT COUNT(*) FROM tasks WHERE id LIKE 'b%'"), "10");
  const auto r = standby.Post("/api/v1/tasks", tasks_body("after", 1), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 201) << r->body;
  expect_epochs_in_order();

  ASSERT_EQ(::kill(standby_->pid, SIGTERM), 0);
  EXPECT_EQ(standby_->wait_exit(), 0) << standby_->seen;
  EXPECT_EQ(one_value(url_, "SELECT COUNT(*) FROM pg_locks WHERE locktype = 'advisory'"), "0")
      << "a clean stop lets go of the lease";
}

TEST_F(ServeFailoverPostgres, AFrozenActiveStepsDownAndWritesAndCommandsNothing) {
  start_pair();
  httplib::Client active("127.0.0.1", std::stoi(active_port_));
  active.set_read_timeout(std::chrono::seconds(60));
  const auto r = active.Post("/api/v1/tasks", tasks_body("s", 3), "application/json");
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  // What it sent the robot while it held the lease is read before the freeze (the test reads a
  // process's output only while it waits on it), so that only what comes after counts below.
  EXPECT_FALSE(active_->wait_for(std::regex(R"(epoch 1: (first task step sent) to the robot)")).empty())
      << active_->seen;

  ASSERT_EQ(::kill(active_->pid, SIGSTOP), 0);
  // Its renewal grows old; the standby cuts it off and takes over.
  EXPECT_FALSE(standby_->wait_for(std::regex(R"(is the active executive at epoch (2))")).empty()) << standby_->seen;
  EXPECT_FALSE(standby_->wait_for(kActiveAt).empty()) << standby_->seen;
  const std::string takeover_seq = one_value(url_, "SELECT seq FROM events WHERE event = 'takeover' AND epoch = 2");
  ASSERT_FALSE(takeover_seq.empty());
  const std::size_t seen_before = active_->seen.size();
  ASSERT_EQ(::kill(active_->pid, SIGCONT), 0);

  // Resumed, it finds the lease lost and steps down, a standby again.
  EXPECT_FALSE(active_->wait_for(std::regex(R"(lost the lease at epoch (1))")).empty()) << active_->seen;
  EXPECT_FALSE(active_->wait_for(std::regex(R"(rondo serve: (standby) again)")).empty()) << active_->seen;
  EXPECT_FALSE(active_->wait_for(kStandbyAt).empty()) << active_->seen;
  const std::string after = active_->seen.substr(seen_before);
  EXPECT_EQ(after.find("first task step sent"), std::string::npos) << "it commanded the robot:\n" << after;
  httplib::Client old("127.0.0.1", std::stoi(active_port_));
  old.set_read_timeout(std::chrono::seconds(60));
  ASSERT_TRUE(eventually([&] {
    const auto h = old.Get("/healthz");
    return h && body_of(h)["status"] == "standby";
  }, seconds(60)));
  const auto m = old.Get("/metrics");
  ASSERT_TRUE(m);
  EXPECT_NE(m->body.find("rondo_step_downs_total 1"), std::string::npos) << m->body;

  // Nothing written at epoch 1 after the takeover; every task is still there.
  EXPECT_EQ(one_value(url_, "SELECT COUNT(*) FROM events WHERE epoch = 1 AND seq > " + takeover_seq), "0");
  EXPECT_EQ(one_value(url_, "SELECT COUNT(*) FROM tasks WHERE id LIKE 's-%'"), "3");
  expect_epochs_in_order();

  for (Child* c : {&*active_, &*standby_}) {
    ASSERT_EQ(::kill(c->pid, SIGTERM), 0);
    EXPECT_EQ(c->wait_exit(), 0) << c->seen;
  }
}

}  // namespace
}  // namespace rondo::test
