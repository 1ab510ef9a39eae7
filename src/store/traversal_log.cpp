#include "rondo/store/traversal_log.h"


#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string>

#include "store_access.h"
#include "write_tx.h"

namespace rondo::store {
namespace {

// The one INSERT of the log. A stored origin makes it a no-op (0 rows changed); NULL origins never
// conflict, so live traversals are always stored. True if a row was added.
bool insert(db::Connection& db, const Traversal& t) {
  const std::optional<std::string> origin = t.origin.empty() ? std::nullopt : std::optional<std::string>(t.origin);
  return db.exec(
             "INSERT INTO traversals (edge_id, from_node, to_node, start_ms, duration_ms, success, origin, robot, "
             "waited_ms) VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9) ON CONFLICT (origin) DO NOTHING",
             {t.edge_id, t.from, t.to, to_db(t.start), to_db(t.duration), t.success ? 1 : 0, origin, t.robot,
              to_db(t.waited)}) == 1;
}

Traversal traversal_from_row(const db::Rows& row) {
  Traversal t;
  t.edge_id = row.text(0);
  t.from = row.text(1);
  t.to = row.text(2);
  t.start = time_from_db(row.int64(3));
  t.duration = duration_from_db(row.int64(4));
  t.success = row.int64(5) != 0;
  if (!row.is_null(6)) t.origin = row.text(6);
  t.robot = row.text(7);
  t.waited = duration_from_db(row.int64(8));
  return t;
}

}  // namespace

Result<bool> add_traversal(Store& store, const Traversal& traversal) {
  return guarded(store, "adding a traversal", [&]() -> Result<bool> {
    return insert(connection(store), traversal);  // autocommit: its own transaction
  });
}

Result<InsertCounts> add_traversals(Store& store, std::span<const Traversal> traversals, const BatchOptions& options) {
  return guarded(store, "adding traversals", [&]() -> Result<InsertCounts> {
    db::Connection& db = connection(store);
    WriteTx tx(db);
    const std::size_t every = std::max<std::size_t>(options.progress_every, 1);
    InsertCounts counts;
    std::size_t done = 0;
    for (const Traversal& t : traversals) {
      ++(insert(db, t) ? counts.inserted : counts.already_present);
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
        "SELECT edge_id, from_node, to_node, start_ms, duration_ms, success, origin, robot, waited_ms FROM traversals "
        "WHERE TRUE";
    db::Params params;
    const auto where = [&](std::string_view condition, db::Param value) {
      params.push_back(std::move(value));
      sql += fmt::format(" AND {} ${}", condition, params.size());
    };
    if (query.edge_id) where("edge_id =", *query.edge_id);
    if (query.robot) where("robot =", *query.robot);
    if (query.from) where("start_ms >=", to_db(*query.from));
    if (query.until) where("start_ms <", to_db(*query.until));
    sql += " ORDER BY start_ms, edge_id, id";
    auto select = connection(store).query(sql, params);
    std::vector<Traversal> out;
    while (select->next()) out.push_back(traversal_from_row(*select));
    return out;
  });
}

Result<std::size_t> count_traversals(const Store& store) {
  return guarded(store, "counting traversals", [&]() -> Result<std::size_t> {
    return static_cast<std::size_t>(db::query_int64(connection(store), "SELECT COUNT(*) FROM traversals").value_or(0));
  });
}

}  // namespace rondo::store
