// What only the PostgreSQL backend has: store URLs and where their password comes from, connection
// failures, the schema stamp and its migrations, read-only sessions, and two processes migrating an
// empty database at once. (Everything the two backends share runs on both: store_backends.h.)
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "app/cli_runner.h"
#include "db/pg_connection.h"
#include "migrations.h"
#include "rondo/store/backup.h"
#include "rondo/store/batch.h"
#include "rondo/store/events.h"
#include "rondo/store/request_watch.h"
#include "rondo/store/requests.h"
#include "rondo/store/store.h"
#include "rondo/store/task_table.h"
#include "rondo/store/traversal_log.h"
#include "store/pg_cluster.h"
#include "store/temp_db.h"
#include "store_access.h"

namespace rondo::store {
namespace {

using testing::PgCluster;
using testing::run_sql;
using testing::TempDb;

Time at(int s) {
  return Time{seconds(s)};
}

// PGPASSWORD set for the life of one object.
class PasswordInEnvironment {
 public:
  explicit PasswordInEnvironment(const char* password) { ::setenv("PGPASSWORD", password, 1); }
  ~PasswordInEnvironment() { ::unsetenv("PGPASSWORD"); }
  PasswordInEnvironment(const PasswordInEnvironment&) = delete;
  PasswordInEnvironment& operator=(const PasswordInEnvironment&) = delete;
};

class PostgresStore : public ::testing::Test {
 protected:
  void SetUp() override {
    try {
      url_ = PgCluster::get().create_database();
    } catch (const std::exception& e) {
      FAIL() << e.what();
    }
  }
  StoreLocation location() const { return StoreLocation::postgres(url_).value(); }
  std::string url_;
};

TEST(PostgresStoreUrl, NamesTheBackendByItsScheme) {
  const auto pg = StoreLocation::parse("postgresql://rondo@db.example:5433/fleet?sslmode=disable");
  ASSERT_TRUE(pg.ok()) << pg.error().message;
  EXPECT_EQ(pg->kind, StoreLocation::Kind::kPostgres);
  EXPECT_EQ(pg->name(), "postgresql://rondo@db.example:5433/fleet?sslmode=disable");
  EXPECT_EQ(StoreLocation::parse("postgres://db/fleet")->kind, StoreLocation::Kind::kPostgres);
  const auto file = StoreLocation::parse("run/rondo.sqlite");
  ASSERT_TRUE(file.ok());
  EXPECT_EQ(file->kind, StoreLocation::Kind::kSqlite);
  EXPECT_EQ(file->file, "run/rondo.sqlite");
}

TEST(PostgresStoreUrl, AMalformedUrlIsBadInputNamingIt) {
  const auto bad = StoreLocation::parse("postgresql://db/fleet?no_such_option=1");
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(bad.error().message.find("no_such_option"), std::string::npos) << bad.error().message;
}

TEST(PostgresStoreUrl, APasswordInTheUrlIsRefusedAndNotRepeated) {
  for (const char* url : {"postgresql://rondo:s3cret@db/fleet", "postgresql://rondo@db/fleet?password=s3cret"}) {
    const auto refused = StoreLocation::parse(url);
    ASSERT_FALSE(refused.ok()) << url;
    EXPECT_EQ(refused.error().code, ErrorCode::kInvalidInput);
    EXPECT_NE(refused.error().message.find("password"), std::string::npos) << refused.error().message;
    EXPECT_EQ(refused.error().message.find("s3cret"), std::string::npos) << refused.error().message;
  }
}

TEST_F(PostgresStore, OpensMigratesAndStampsTheDatabase) {
  auto db = Store::open(location());
  ASSERT_TRUE(db.ok()) << db.error().message;
  EXPECT_TRUE(db->is_postgres());
  EXPECT_EQ(db->schema_version().value(), Store::latest_schema_version());
  EXPECT_EQ(pg_migrations().size(), sqlite_migrations().size());
  for (std::size_t i = 0; i < pg_migrations().size(); ++i) {
    EXPECT_EQ(pg_migrations()[i].version, sqlite_migrations()[i].version);
    EXPECT_EQ(pg_migrations()[i].description, sqlite_migrations()[i].description);
  }
  // Opening again migrates nothing and keeps what is stored.
  ASSERT_TRUE(add_task(*db, {"t1", Json::object(), "queued", at(1), at(1)}).ok());
  auto again = Store::open(location(), {.mode = OpenMode::kMustExist});
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_TRUE(get_task(*again, "t1").ok());
}

TEST_F(PostgresStore, TheSessionHasAStatementTimeout) {
  auto db = Store::open(location(), {.statement_timeout = std::chrono::milliseconds(1500)});
  ASSERT_TRUE(db.ok()) << db.error().message;
  EXPECT_EQ(db::query_text(connection(*db), "SHOW statement_timeout"), "1500ms");
  auto fallback = Store::open(location());
  ASSERT_TRUE(fallback.ok());
  EXPECT_EQ(db::query_text(connection(*fallback), "SHOW statement_timeout"), "1min");
  auto none = Store::open(location(), {.statement_timeout = Duration{0}});
  ASSERT_TRUE(none.ok());
  EXPECT_EQ(db::query_text(connection(*none), "SHOW statement_timeout"), "0");
}

TEST_F(PostgresStore, AnEmptyDatabaseIsNoStoreForReadersAndMustExist) {
  for (OpenMode mode : {OpenMode::kMustExist, OpenMode::kReadOnly}) {
    auto db = Store::open(location(), {.mode = mode});
    ASSERT_FALSE(db.ok());
    EXPECT_EQ(db.error().code, ErrorCode::kNotFound);
    EXPECT_NE(db.error().message.find(url_), std::string::npos) << db.error().message;
  }
  EXPECT_EQ(run_sql(url_, "SELECT 1 FROM rondo_store").find("does not exist") != std::string::npos, true)
      << "nothing was created";
}

TEST_F(PostgresStore, ADatabaseOfSomethingElseIsRefusedUntouched) {
  ASSERT_EQ(run_sql(url_, "CREATE TABLE invoices (id INTEGER)"), "");
  auto db = Store::open(location());
  ASSERT_FALSE(db.ok());
  EXPECT_EQ(db.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(db.error().message.find("not a rondo database"), std::string::npos) << db.error().message;
  EXPECT_NE(run_sql(url_, "SELECT 1 FROM tasks"), "") << "no rondo table was made";
}

TEST_F(PostgresStore, ANewerSchemaIsRefused) {
  ASSERT_TRUE(Store::open(location()).ok());
  ASSERT_EQ(run_sql(url_, "UPDATE rondo_store SET schema_version = 99"), "");
  auto db = Store::open(location());
  ASSERT_FALSE(db.ok());
  EXPECT_EQ(db.error().code, ErrorCode::kUnsupported);
  EXPECT_NE(db.error().message.find("99"), std::string::npos) << db.error().message;
}

// Version 1 -> latest on PostgreSQL: old events keep their sequence numbers and new ones follow
// them (the identity continues after the copied rows); a single robot's rows get its name.
TEST_F(PostgresStore, DataOfVersionOneIsMigratedToTheLatest) {
  {
    auto raw = db::PgConnection::connect({.conninfo = url_, .password = std::nullopt});
    ASSERT_TRUE(migrate(*raw, pg_migrations().first(1), url_).ok());
  }
  ASSERT_EQ(run_sql(url_,
                    "INSERT INTO tasks (id, state, task_json, created_ms, updated_ms) VALUES "
                    "('t1', 'failed', '{}', 10, 30), ('t2', 'queued', '{}', 20, 20);"
                    "INSERT INTO task_events (time_ms, task_id, event, reason) VALUES (10, 't1', 'queued', 'added'), "
                    "(20, 't2', 'queued', 'added'), (30, 't1', 'failed', 'too late')"),
            "");
  auto db = Store::open(location());
  ASSERT_TRUE(db.ok()) << db.error().message;
  const auto events = read_events(*db);
  ASSERT_TRUE(events.ok());
  ASSERT_EQ(events->size(), 3u);
  EXPECT_EQ((*events)[2].seq, 3);
  EXPECT_EQ((*events)[2].reason, "too late");
  EXPECT_EQ((*events)[2].robot, "robot");
  EXPECT_EQ(get_task(*db, "t1")->robot, "robot");
  const auto next = append_event(*db, {.time = at(40), .task_id = "t2", .event = "navigating"});
  ASSERT_TRUE(next.ok()) << next.error().message;
  EXPECT_EQ(*next, 4);
}

TEST_F(PostgresStore, AReadOnlyOpenWritesNothing) {
  ASSERT_TRUE(Store::open(location()).ok());
  auto reader = Store::open(location(), {.mode = OpenMode::kReadOnly});
  ASSERT_TRUE(reader.ok()) << reader.error().message;
  const Status added = add_task(*reader, {"t1", Json::object(), "queued", at(1), at(1)});
  ASSERT_FALSE(added.ok());
  EXPECT_EQ(added.error().code, ErrorCode::kStorage);
  EXPECT_NE(added.error().message.find("read-only"), std::string::npos) << added.error().message;
}

TEST_F(PostgresStore, FourConnectionsOpeningAnEmptyDatabaseAtOnceMigrateItOnce) {
  std::vector<Result<Store>> opened;
  opened.reserve(4);
  for (int i = 0; i < 4; ++i) opened.push_back(Error::internal("not opened"));
  std::vector<std::thread> openers;
  for (int i = 0; i < 4; ++i) openers.emplace_back([&, i] { opened[static_cast<std::size_t>(i)] = Store::open(location()); });
  for (std::thread& t : openers) t.join();
  for (const auto& db : opened) ASSERT_TRUE(db.ok()) << db.error().message;
  EXPECT_EQ(opened[0]->schema_version().value(), Store::latest_schema_version());
}

// A server that is not there: a clear error naming the URL, well within the connect timeout.
TEST(PostgresStoreConnect, AnUnreachableServerIsBadInputNamingTheUrl) {
  std::string url;
  try {
    url = PgCluster::get().tcp_url("nowhere", "rondo") ;
  } catch (const std::exception& e) {
    FAIL() << e.what();
  }
  // The cluster's port with 1 added: nothing listens there (the test fails, not hangs, if it does).
  const std::string port = std::to_string(PgCluster::get().port());
  url.replace(url.find(port), port.size(), std::to_string(PgCluster::get().port() + 1));
  const auto began = std::chrono::steady_clock::now();
  auto db = Store::open(StoreLocation::postgres(url + "?connect_timeout=3").value());
  const auto took = std::chrono::steady_clock::now() - began;
  ASSERT_FALSE(db.ok());
  EXPECT_EQ(db.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(db.error().message.find(url), std::string::npos) << db.error().message;
  EXPECT_NE(db.error().message.find("cannot connect"), std::string::npos) << db.error().message;
  EXPECT_LT(took, std::chrono::seconds(10));
}

// Over TCP the cluster asks for a password: from a password file, or PGPASSWORD; none is refused.
TEST_F(PostgresStore, ThePasswordComesFromAFileOrTheEnvironment) {
  ASSERT_EQ(run_sql(url_, "CREATE ROLE fleet LOGIN PASSWORD 'p4ss-w0rd'"), "");
  const std::string database = url_.substr(url_.find(":///") + 4, url_.find('?') - url_.find(":///") - 4);
  ASSERT_EQ(run_sql(url_, "GRANT ALL ON SCHEMA public TO fleet; ALTER DATABASE " + database + " OWNER TO fleet"), "");
  const std::string tcp = PgCluster::get().tcp_url(database, "fleet");

  auto none = Store::open(StoreLocation::postgres(tcp).value());
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.error().code, ErrorCode::kInvalidInput);
  EXPECT_NE(none.error().message.find("password"), std::string::npos) << none.error().message;

  TempDb password_file;
  std::ofstream(password_file.path()) << "p4ss-w0rd\n";
  auto with_file = Store::open(StoreLocation::postgres(tcp, password_file.path()).value());
  ASSERT_TRUE(with_file.ok()) << with_file.error().message;
  EXPECT_TRUE(add_task(*with_file, {"t1", Json::object(), "queued", at(1), at(1)}).ok());

  std::ofstream(password_file.path()) << "wrong\n";
  auto wrong = Store::open(StoreLocation::postgres(tcp, password_file.path()).value());
  ASSERT_FALSE(wrong.ok());
  EXPECT_EQ(wrong.error().message.find("wrong"), std::string::npos) << "the password is not repeated";

  auto missing = Store::open(StoreLocation::postgres(tcp, password_file.path().string() + "-gone").value());
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("password_file"), std::string::npos) << missing.error().message;

  PasswordInEnvironment env("p4ss-w0rd");
  auto from_env = Store::open(StoreLocation::postgres(tcp).value());
  ASSERT_TRUE(from_env.ok()) << from_env.error().message;
  EXPECT_TRUE(get_task(*from_env, "t1").ok());
}

// LISTEN/NOTIFY: a queued request wakes the watch at its commit, not before; a watch told nothing
// times out; stop() from another thread ends a wait at once.
TEST_F(PostgresStore, AQueuedRequestWakesTheWatchWhenItCommits) {
  auto db = Store::open(location());
  ASSERT_TRUE(db.ok()) << db.error().message;
  auto watch = RequestWatch::open(location());
  ASSERT_TRUE(watch.ok()) << watch.error().message;
  EXPECT_EQ((*watch)->wait(Duration{20}).value(), false) << "nothing queued yet";
  {
    Batch batch(*db);
    ASSERT_TRUE(queue_request(*db, {.queued = at(1), .source = "words", .sentence = "s", .body = Json::object()}).ok());
    EXPECT_EQ((*watch)->wait(Duration{20}).value(), false) << "not committed yet";
    ASSERT_TRUE(batch.commit().ok());
  }
  const auto began = std::chrono::steady_clock::now();
  EXPECT_EQ((*watch)->wait(seconds(30)).value(), true);
  EXPECT_LT(std::chrono::steady_clock::now() - began, std::chrono::seconds(5));
  EXPECT_EQ((*watch)->wait(Duration{20}).value(), false) << "one notification, taken once";

  std::thread stopper([&] { (*watch)->stop(); });
  EXPECT_EQ((*watch)->wait(seconds(30)).value(), false);
  stopper.join();
}

// rondo backup on PostgreSQL: pg_dump's archive, restored by pg_restore into an empty database,
// holds the same tasks and events, and the log's sequence numbers go on after the restored ones.
TEST_F(PostgresStore, ABackupRestoresToTheSameStore) {
  auto db = Store::open(location());
  ASSERT_TRUE(db.ok()) << db.error().message;
  for (const char* id : {"t1", "t2"}) ASSERT_TRUE(add_task(*db, {id, Json::object(), "queued", at(1), at(1)}).ok());
  ASSERT_TRUE(set_task_state(*db, "t1", "failed", at(5), "too late", "late").ok());
  TempDb file;
  auto report = backup_store(*db, file.path());
  ASSERT_TRUE(report.ok()) << report.error().message;
  EXPECT_GT(report->bytes, 0u);
  EXPECT_FALSE(std::filesystem::exists(file.path().string() + ".part"));
  EXPECT_EQ(backup_store(*db, file.path()).error().code, ErrorCode::kInvalidInput) << "never overwrites";

  const std::string restored = PgCluster::get().create_database();
  const std::string restore = "pg_restore --no-owner --dbname='" + restored + "' '" + file.str() + "' 2>&1";
  ASSERT_EQ(std::system(restore.c_str()), 0) << restore;
  auto back = Store::open(StoreLocation::postgres(restored).value(), {.mode = OpenMode::kMustExist});
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(*list_tasks(*back), *list_tasks(*db));
  EXPECT_EQ(*read_events(*back), *read_events(*db));
  const auto next = append_event(*back, {.time = at(9), .task_id = "t2", .event = "navigating"});
  ASSERT_TRUE(next.ok()) << next.error().message;
  EXPECT_EQ(*next, read_events(*db)->back().seq + 1);
}

// The log commands take a URL for --db, and the two backends report the same numbers.
TEST_F(PostgresStore, LogImportAndStatsOnAUrlMatchSqlite) {
  TempDb file;
  for (const std::string& db : {url_, file.str()}) {
    const auto imported = test::run_cli({"log", "import", "--witham", testing::witham_dir().string(), "--db", db});
    ASSERT_EQ(imported.exit_code, 0) << db << ": " << imported.err;
  }
  const auto on_pg = test::run_cli({"log", "stats", "--db", url_});
  const auto on_sqlite = test::run_cli({"log", "stats", "--db", file.str()});
  ASSERT_EQ(on_pg.exit_code, 0) << on_pg.err;
  EXPECT_EQ(on_pg.out, on_sqlite.out);
  EXPECT_NE(on_pg.out.find("total (62 edges)"), std::string::npos) << on_pg.out;
}

// Retention on PostgreSQL: the same rows move as from an SQLite store (gtest_backup.cpp), into an
// SQLite archive; the event log is append-only again afterwards, and a second run moves nothing.
TEST_F(PostgresStore, ArchivesOldRecordsIntoAnSqliteFile) {
  auto db = Store::open(location());
  ASSERT_TRUE(db.ok()) << db.error().message;
  const auto day = [](int d, int hour) { return Time{hours(24 * d + hour)}; };
  for (int d = 0; d < 30; ++d) {
    const std::string id = "day" + std::to_string(d);
    ASSERT_TRUE(add_task(*db, {.id = id, .task = Json{{"id", id}}, .state = "queued", .created = day(d, 8),
                               .updated = day(d, 8), .source = "test"}));
    ASSERT_TRUE(set_task_state(*db, id, "succeeded", day(d, 9), "done", "done"));
    ASSERT_TRUE(add_traversal(*db, {.edge_id = "e", .from = "a", .to = "b", .start = day(d, 10),
                                    .duration = seconds(30), .success = true}));
    ASSERT_TRUE(append_event(*db, {.time = day(d, 11), .subject = Subject::kRobot, .about = "robot",
                                   .event = "battery", .code = "battery"}));
  }
  ASSERT_TRUE(add_task(*db, {.id = "waiting", .task = Json{{"id", "waiting"}}, .state = "queued", .created = day(0, 7),
                             .updated = day(0, 7)}));
  TempDb file;
  const auto r = archive_old_records(*db, hours(24 * 20), hours(24 * 14), file.path());
  ASSERT_TRUE(r.ok()) << r.error().message;
  EXPECT_EQ(*r->cut, day(9, 11));
  EXPECT_EQ(r->tasks, 10);
  EXPECT_EQ(r->traversals, 10);
  EXPECT_EQ(r->events, 10 * 2 + 9);
  SQLite::Database archive(file.str(), SQLite::OPEN_READONLY);
  EXPECT_EQ(archive.execAndGet("SELECT COUNT(*) FROM tasks").getInt64(), 10);
  EXPECT_EQ(archive.execAndGet("SELECT COUNT(*) FROM events").getInt64(), 29);
  EXPECT_EQ(archive.execAndGet("SELECT COUNT(*) FROM traversals").getInt64(), 10);
  EXPECT_EQ(archive.execAndGet("SELECT task_json FROM tasks WHERE id = 'day3'").getString(), R"({"id":"day3"})");
  EXPECT_EQ(list_tasks(*db).value().size(), 21u);
  EXPECT_TRUE(get_task(*db, "waiting").ok());
  EXPECT_NE(run_sql(url_, "DELETE FROM events"), "") << "append-only again";
  const auto again = archive_old_records(*db, hours(24 * 20), hours(24 * 14), file.path());
  ASSERT_TRUE(again.ok()) << again.error().message;
  EXPECT_EQ(again->tasks + again->events + again->traversals, 0);
}

TEST(PostgresStoreWatch, AnSqliteStoreHasNoNotificationsToWatch) {
  TempDb tmp;
  auto watch = RequestWatch::open(StoreLocation::sqlite(tmp.path()));
  ASSERT_FALSE(watch.ok());
  EXPECT_EQ(watch.error().code, ErrorCode::kUnsupported);
}

}  // namespace
}  // namespace rondo::store
