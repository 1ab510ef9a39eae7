// Private to rondo::store: the small database seam under the store's tables. A Connection runs SQL
// with numbered parameters ($1, $2, ... in both backends), reads rows through a forward cursor, and
// says whether a transaction is open; SqliteConnection (sqlite_connection.h) and PgConnection
// (pg_connection.h) implement it. What differs between the two SQL dialects lives in dialect.h.
//
//   std::int64_t changed = db.exec("UPDATE tasks SET state = $1 WHERE id = $2", {"failed", id});
//   auto rows = db.query("SELECT id FROM tasks WHERE state = $1", {"queued"});
//   while (rows->next()) ids.push_back(rows->text(0));
//
// Every failure is thrown as db::Failure, which the store's guarded() (store_access.h) turns into
// an rondo::Error naming the store and what it was doing.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rondo::store::db {

enum class Backend { kSqlite, kPostgres };

// What went wrong, as far as the store's callers care.
enum class FailureKind {
  kStorage,        // anything else: locked, full, a constraint refused the write, connection lost
  kNotADatabase,   // the file or server holds something that is not a database we can read
  kCorrupt,        // the database itself is damaged
  kUnreachable,    // no connection could be made (bad address, server down, refused login)
  kFenced,         // the database refused a write of a stale epoch: another executive is active
};

class Failure : public std::runtime_error {
 public:
  Failure(FailureKind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  FailureKind kind() const { return kind_; }

 private:
  FailureKind kind_;
};

// One parameter value: NULL, an integer, a real or text.
class Param {
 public:
  Param(std::nullopt_t) {}  // NOLINT(google-explicit-constructor): NULL
  Param(std::int64_t v) : value_(v) {}                  // NOLINT(google-explicit-constructor)
  Param(int v) : value_(std::int64_t{v}) {}             // NOLINT(google-explicit-constructor)
  Param(double v) : value_(v) {}                        // NOLINT(google-explicit-constructor)
  Param(std::string v) : value_(std::move(v)) {}        // NOLINT(google-explicit-constructor)
  Param(std::string_view v) : value_(std::string(v)) {}  // NOLINT(google-explicit-constructor)
  Param(const char* v) : value_(std::string(v)) {}      // NOLINT(google-explicit-constructor)
  template <class T>
  Param(const std::optional<T>& v) {  // NOLINT(google-explicit-constructor): NULL when empty
    if (v) *this = Param(*v);
  }

  bool is_null() const { return std::holds_alternative<std::monostate>(value_); }
  const std::variant<std::monostate, std::int64_t, double, std::string>& value() const { return value_; }

 private:
  std::variant<std::monostate, std::int64_t, double, std::string> value_;
};

using Params = std::vector<Param>;

// A forward cursor over a query's rows. Columns are numbered from 0. Reading a NULL column gives
// 0, 0.0 or "" (check is_null first where NULL means something).
class Rows {
 public:
  virtual ~Rows() = default;
  // Moves to the next row; false at the end.
  virtual bool next() = 0;
  virtual bool is_null(int column) const = 0;
  virtual std::int64_t int64(int column) const = 0;
  virtual double real(int column) const = 0;
  virtual std::string text(int column) const = 0;
};

// One connection. Used by one thread at a time.
class Connection {
 public:
  virtual ~Connection() = default;
  virtual Backend backend() const = 0;

  // Runs one statement; returns the number of rows it changed.
  virtual std::int64_t exec(std::string_view sql, const Params& params = {}) = 0;
  // Runs several statements separated by ';' (schema steps); no parameters.
  virtual void exec_script(std::string_view sql) = 0;
  // Runs one statement that returns rows.
  virtual std::unique_ptr<Rows> query(std::string_view sql, const Params& params = {}) = 0;
  // Runs a statement that returns nothing to read and does not fail where it is used (BEGIN,
  // SAVEPOINT, RELEASE of a savepoint that is open): SQLite at once; PostgreSQL sends it together
  // with the next statement, in one round trip to the server, and a failure of it is that one's.
  virtual void exec_deferred(std::string_view sql) { exec_script(sql); }
  // Whether a transaction is open on this connection.
  virtual bool in_transaction() const = 0;
};

// The first column of the first row, or none (no row, or NULL).
std::optional<std::int64_t> query_int64(Connection& db, std::string_view sql, const Params& params = {});
std::optional<std::string> query_text(Connection& db, std::string_view sql, const Params& params = {});

}  // namespace rondo::store::db
