#include "db/sqlite_connection.h"

#include <sqlite3.h>

#include <fmt/format.h>

#include <type_traits>

namespace rondo::store::db {
namespace {

void bind_all(SQLite::Statement& s, const Params& params) {
  for (std::size_t i = 0; i < params.size(); ++i) {
    const std::string name = fmt::format("${}", i + 1);
    const int index = s.getIndex(name.c_str());
    if (index == 0) throw Failure(FailureKind::kStorage, fmt::format("parameter {} is not in the statement", name));
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, std::monostate>)
            s.bind(index);
          else
            s.bind(index, v);
        },
        params[i].value());
  }
}

}  // namespace

// Reads a statement of the connection's cache (or one of its own); resets it when done.
class SqliteConnection::Cursor final : public Rows {
 public:
  Cursor(SQLite::Statement& statement, Cached* slot, std::unique_ptr<SQLite::Statement> own)
      : statement_(statement), slot_(slot), own_(std::move(own)) {}
  ~Cursor() override {
    (void)statement_.tryReset();  // an error of the last step is the reader's, reported already
    if (slot_) slot_->busy = false;
  }
  bool next() override {
    try {
      return statement_.executeStep();
    } catch (const SQLite::Exception& e) {
      throw sqlite_failure(e);
    }
  }
  bool is_null(int column) const override { return statement_.isColumnNull(column); }
  std::int64_t int64(int column) const override { return statement_.getColumn(column).getInt64(); }
  double real(int column) const override { return statement_.getColumn(column).getDouble(); }
  std::string text(int column) const override { return statement_.getColumn(column).getString(); }

 private:
  SQLite::Statement& statement_;
  Cached* slot_;
  std::unique_ptr<SQLite::Statement> own_;
};

Failure sqlite_failure(const SQLite::Exception& e) {
  const int primary = e.getErrorCode() & 0xff;
  if (primary == SQLITE_NOTADB) return Failure(FailureKind::kNotADatabase, e.what());
  if (primary == SQLITE_CORRUPT) return Failure(FailureKind::kCorrupt, e.what());
  return Failure(FailureKind::kStorage, e.what());
}

SqliteConnection::SqliteConnection(std::unique_ptr<SQLite::Database> database)
    : owned_(std::move(database)), database_(*owned_) {}
SqliteConnection::SqliteConnection(SQLite::Database& database) : database_(database) {}
SqliteConnection::~SqliteConnection() = default;

std::map<std::string, SqliteConnection::Cached, std::less<>>::iterator SqliteConnection::cached(std::string_view sql) {
  auto it = cache_.find(sql);
  if (it != cache_.end()) return it;
  // SQL texts made with values in them (retention) would grow the cache without end: past a
  // bound, the statements no cursor reads are dropped.
  if (cache_.size() >= kCacheLimit) std::erase_if(cache_, [](const auto& entry) { return !entry.second.busy; });
  return cache_.emplace(std::string(sql), Cached{}).first;
}

SQLite::Statement& SqliteConnection::prepare(Cached& slot, std::string_view sql, const Params& params) {
  if (!slot.statement) slot.statement = std::make_unique<SQLite::Statement>(database_, std::string(sql));
  // tryReset: reset() would throw again the error of the statement's last run (a refused write).
  (void)slot.statement->tryReset();
  slot.statement->clearBindings();
  bind_all(*slot.statement, params);
  return *slot.statement;
}

std::int64_t SqliteConnection::exec(std::string_view sql, const Params& params) {
  try {
    auto it = cached(sql);
    if (it->second.busy) {  // a cursor reads this text: a statement of its own
      SQLite::Statement s(database_, std::string(sql));
      bind_all(s, params);
      return s.exec();
    }
    SQLite::Statement& s = prepare(it->second, sql, params);
    const int changed = s.exec();
    (void)s.tryReset();
    return changed;
  } catch (const SQLite::Exception& e) {
    throw sqlite_failure(e);
  }
}

void SqliteConnection::exec_script(std::string_view sql) {
  try {
    database_.exec(std::string(sql));
  } catch (const SQLite::Exception& e) {
    throw sqlite_failure(e);
  }
}

std::unique_ptr<Rows> SqliteConnection::query(std::string_view sql, const Params& params) {
  try {
    auto it = cached(sql);
    if (it->second.busy) {
      auto own = std::make_unique<SQLite::Statement>(database_, std::string(sql));
      bind_all(*own, params);
      SQLite::Statement& s = *own;
      return std::make_unique<Cursor>(s, nullptr, std::move(own));
    }
    SQLite::Statement& s = prepare(it->second, sql, params);
    it->second.busy = true;
    return std::make_unique<Cursor>(s, &it->second, nullptr);
  } catch (const SQLite::Exception& e) {
    throw sqlite_failure(e);
  }
}

bool SqliteConnection::in_transaction() const {
  return sqlite3_get_autocommit(database_.getHandle()) == 0;
}

}  // namespace rondo::store::db
