// Private to rondo::store: db::Connection on a PostgreSQL server (libpq). Each statement goes in
// one round trip with its parameters as text, typed by the server from where they are used;
// deferred statements (BEGIN, SAVEPOINT, RELEASE) wait and go with the next one, in the same round
// trip (libpq's pipeline mode, or one simple-protocol message for a script). Server notices are
// not printed. Errors are thrown as db::Failure.
//
//   auto db = PgConnection::connect({.conninfo = "postgresql://rondo@db/rondo", .password = pw});
//   db->exec("SET synchronous_commit = off");
#pragma once

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "db/connection.h"

struct pg_conn;
struct pg_result;

namespace rondo::store::db {

struct PgAddress {
  std::string conninfo;                 // a libpq URI or "key=value ..." string, with no password
  std::optional<std::string> password;  // from a password file; none: libpq's own ways (PGPASSWORD, ~/.pgpass)
  std::chrono::seconds connect_timeout{5};
  std::string application_name = "rondo";
};

class PgConnection final : public Connection {
 public:
  // Throws Failure(kUnreachable) naming why libpq could not connect.
  static std::unique_ptr<PgConnection> connect(const PgAddress& address);
  ~PgConnection() override;
  PgConnection(const PgConnection&) = delete;
  PgConnection& operator=(const PgConnection&) = delete;

  Backend backend() const override { return Backend::kPostgres; }
  std::int64_t exec(std::string_view sql, const Params& params = {}) override;
  void exec_script(std::string_view sql) override;
  std::unique_ptr<Rows> query(std::string_view sql, const Params& params = {}) override;
  void exec_deferred(std::string_view sql) override;
  bool in_transaction() const override;

  pg_conn* raw() { return conn_; }

 private:
  explicit PgConnection(pg_conn* conn) : conn_(conn) {}
  // Runs `sql` after the deferred statements, in one round trip; the caller frees the result.
  pg_result* run(std::string_view sql, const Params& params);
  pg_result* run_pipelined(const std::string& sql, const Params& params);
  pg_conn* conn_;
  std::vector<std::string> deferred_;  // sent with the next statement
};

}  // namespace rondo::store::db
