// Private to rondo::store: db::Connection on an SQLite database (SQLiteCpp). Parameters are named
// $1, $2, ... in the SQL and bound by those names. Prepared statements are kept per SQL text and
// reused. SQLite's own errors are thrown as db::Failure.
//
//   SqliteConnection db(std::make_unique<SQLite::Database>(file, SQLite::OPEN_READWRITE));
//   db.exec("PRAGMA foreign_keys = ON");
#pragma once

#include <SQLiteCpp/Database.h>
#include <SQLiteCpp/Exception.h>
#include <SQLiteCpp/Statement.h>

#include <map>
#include <memory>
#include <string>

#include "db/connection.h"

namespace rondo::store::db {

class SqliteConnection final : public Connection {
 public:
  // Owns `database`.
  explicit SqliteConnection(std::unique_ptr<SQLite::Database> database);
  // Uses `database`, which must outlive this connection (tests, and the migration runner on a raw file).
  explicit SqliteConnection(SQLite::Database& database);
  ~SqliteConnection() override;

  Backend backend() const override { return Backend::kSqlite; }
  std::int64_t exec(std::string_view sql, const Params& params = {}) override;
  void exec_script(std::string_view sql) override;
  std::unique_ptr<Rows> query(std::string_view sql, const Params& params = {}) override;
  bool in_transaction() const override;

  // SQLite's own API, for what only SQLite has (online backup, ATTACH, PRAGMAs).
  SQLite::Database& raw() { return database_; }

 private:
  struct Cached {
    std::unique_ptr<SQLite::Statement> statement;
    bool busy = false;  // a cursor is reading it
  };
  class Cursor;
  static constexpr std::size_t kCacheLimit = 64;
  std::map<std::string, Cached, std::less<>>::iterator cached(std::string_view sql);
  // A prepared statement for `sql` with `params` bound: the cached one when it is free.
  SQLite::Statement& prepare(Cached& slot, std::string_view sql, const Params& params);

  std::unique_ptr<SQLite::Database> owned_;
  SQLite::Database& database_;
  std::map<std::string, Cached, std::less<>> cache_;
};

// The db::Failure for an SQLite error.
Failure sqlite_failure(const SQLite::Exception& e);

}  // namespace rondo::store::db
