// One write of the store, all or nothing: its own write transaction (committed, and with synced
// commits on disk, by commit()), or, inside a store::Batch (batch.h) or another write, a savepoint
// of the transaction already open, which the outer commit makes durable. Not committed by the time
// it is destroyed (an error, an exception): undone. The same on both backends (on PostgreSQL a
// failed statement spoils the transaction; rolling back to the savepoint mends it, as in SQLite).
#pragma once

#include <string>

#include "db/connection.h"
#include "db/dialect.h"

namespace rondo::store {

class WriteTx {
 public:
  explicit WriteTx(db::Connection& db) : db_(db), nested_(db.in_transaction()) {
    // Deferred: on PostgreSQL it travels with the first statement of the write (one round trip).
    db_.exec_deferred(nested_ ? "SAVEPOINT rondo_write" : std::string(db::begin_write(db.backend())));
  }
  WriteTx(const WriteTx&) = delete;
  WriteTx& operator=(const WriteTx&) = delete;
  ~WriteTx() {
    if (done_) return;
    try {
      db_.exec_script(nested_ ? "ROLLBACK TO rondo_write; RELEASE rondo_write" : "ROLLBACK");
    } catch (...) {  // NOLINT(bugprone-empty-catch): a failed rollback leaves the database's own
    }
  }
  void commit() {
    if (nested_)
      db_.exec_deferred("RELEASE rondo_write");  // travels with the next statement, at the latest the COMMIT
    else
      db_.exec_script("COMMIT");
    done_ = true;
  }

 private:
  db::Connection& db_;
  bool nested_;
  bool done_ = false;
};

}  // namespace rondo::store
