#include "rondo/store/traversal_log.h"

#include <SQLiteCpp/Statement.h>
#include "write_tx.h"

#include <algorithm>
#include <string>

#include "sqlite_error.h"

namespace rondo::store {
namespace {

// The one INSERT of the log. A stored origin makes it a no-op (exec() returns 0 changes); NULL
// origins never conflict, so live traversals are always stored.
constexpr const char* kInsert =
    "INSERT INTO traversals (edge_id, from_node, to_node, start_ms, duration_ms, success, origin, robot) "
    "VALUES (?, ?, ?, ?, ?, ?, ?, ?) ON CONFLICT (origin) DO NOTHING";

// Binds `t` to a prepared kInsert, runs it, and resets it for reuse; true if a row was added.
bool insert(SQLite::Statement& statement, const Traversal& t) {
  statement.bind(1, t.edge_id);
  statement.bind(2, t.from);
  statement.bind(3, t.to);
  statement.bind(4, to_db(t.start));
  statement.bind(5, to_db(t.duration));
  statement.bind(6, t.success ? 1 : 0);
  if (t.origin.empty()) {
    statement.bind(7);  // NULL
  } else {
    statement.bind(7, t.origin);
  }
  statement.bind(8, t.robot);
  const int changed = statement.exec();
  statement.reset();
  return changed == 1;
}

Traversal traversal_from_row(const SQLite::Statement& row) {
  Traversal t;
  t.edge_id = row.getColumn(0).getString();
  t.from = row.getColumn(1).getString();
  t.to = row.getColumn(2).getString();
  t.start = time_from_db(row.getColumn(3).getInt64());
  t.duration = duration_from_db(row.getColumn(4).getInt64());
  t.success = row.getColumn(5).getInt() != 0;
  if (!row.isColumnNull(6)) t.origin = row.getColumn(6).getString();
  t.robot = row.getColumn(7).getString();
  return t;
}

}  // namespace

Result<bool> add_traversal(Store& store, const Traversal& traversal) {
  return guarded(store, "adding a traversal", [&]() -> Result<bool> {
    SQLite::Statement statement(connection(store), kInsert);
    return insert(statement, traversal);  // autocommit: its own transaction
  });
}

Result<InsertCounts> add_traversals(Store& store, std::span<const Traversal> traversals, const BatchOptions& options) {
  return guarded(store, "adding traversals", [&]() -> Result<InsertCounts> {
    SQLite::Database& db = connection(store);
    WriteTx tx(db);
    SQLite::Statement statement(db, kInsert);
    const std::size_t every = std::max<std::size_t>(options.progress_every, 1);
    InsertCounts counts;
    std::size_t done = 0;
    for (const Traversal& t : traversals) {
      ++(insert(statement, t) ? counts.inserted : counts.already_present);
      ++done;
      if (options.progress && done % every == 0) options.progress(done, traversals.size());
    }
    tx.commit();
    return counts;
  });
}

Result<std::vector<Traversal>> find_traversals(const Store& store, const TraversalQuery& query) {
  return guarded(store, "reading traversals", [&]() -> Result<std::vector<Traversal>> {
    std::string sql =
        "SELECT edge_id, from_node, to_node, start_ms, duration_ms, success, origin, robot FROM traversals WHERE 1";
    if (query.edge_id) sql += " AND edge_id = :edge";
    if (query.robot) sql += " AND robot = :robot";
    if (query.from) sql += " AND start_ms >= :from";
    if (query.until) sql += " AND start_ms < :until";
    sql += " ORDER BY start_ms, edge_id, id";
    SQLite::Statement select(connection(store), sql);
    if (query.edge_id) select.bind(":edge", *query.edge_id);
    if (query.robot) select.bind(":robot", *query.robot);
    if (query.from) select.bind(":from", to_db(*query.from));
    if (query.until) select.bind(":until", to_db(*query.until));
    std::vector<Traversal> out;
    while (select.executeStep()) out.push_back(traversal_from_row(select));
    return out;
  });
}

Result<std::size_t> count_traversals(const Store& store) {
  return guarded(store, "counting traversals", [&]() -> Result<std::size_t> {
    SQLite::Statement count(connection(store), "SELECT COUNT(*) FROM traversals");
    count.executeStep();
    return static_cast<std::size_t>(count.getColumn(0).getInt64());
  });
}

}  // namespace rondo::store
