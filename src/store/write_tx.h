// One write of the store, all or nothing: its own IMMEDIATE transaction (committed, and with
// synced commits on disk, by commit()), or, inside a store::Batch (batch.h) or another write, a
// savepoint of the transaction already open, which the outer commit makes durable. Not committed
// by the time it is destroyed (an error, an exception): undone.
#pragma once

#include <SQLiteCpp/Database.h>
#include <sqlite3.h>

namespace rondo::store {

class WriteTx {
 public:
  explicit WriteTx(SQLite::Database& db) : db_(db), nested_(sqlite3_get_autocommit(db.getHandle()) == 0) {
    db_.exec(nested_ ? "SAVEPOINT rondo_write" : "BEGIN IMMEDIATE");
  }
  WriteTx(const WriteTx&) = delete;
  WriteTx& operator=(const WriteTx&) = delete;
  ~WriteTx() {
    if (done_) return;
    try {
      db_.exec(nested_ ? "ROLLBACK TO rondo_write; RELEASE rondo_write" : "ROLLBACK");
    } catch (...) {  // NOLINT(bugprone-empty-catch): a failed rollback leaves SQLite's own
    }
  }
  void commit() {
    db_.exec(nested_ ? "RELEASE rondo_write" : "COMMIT");
    done_ = true;
  }

 private:
  SQLite::Database& db_;
  bool nested_;
  bool done_ = false;
};

}  // namespace rondo::store
