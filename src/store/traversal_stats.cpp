#include "rondo/store/traversal_stats.h"

#include <SQLiteCpp/Statement.h>

#include <cmath>

#include "sqlite_error.h"

namespace rondo::store {

Result<TraversalSummary> summarize_traversals(const Store& store) {
  return guarded(store, "summarising traversals", [&]() -> Result<TraversalSummary> {
    SQLite::Statement select(
        connection(store),
        "SELECT edge_id, from_node, to_node, COUNT(*), SUM(success), MIN(start_ms), MAX(start_ms), "
        "AVG(CASE WHEN success = 1 THEN duration_ms END) "
        "FROM traversals GROUP BY edge_id, from_node, to_node ORDER BY edge_id, from_node, to_node");
    TraversalSummary summary;
    while (select.executeStep()) {
      EdgeSummary e;
      e.edge_id = select.getColumn(0).getString();
      e.from = select.getColumn(1).getString();
      e.to = select.getColumn(2).getString();
      e.attempts = select.getColumn(3).getInt64();
      e.successes = select.getColumn(4).getInt64();
      e.first_start = time_from_db(select.getColumn(5).getInt64());
      e.last_start = time_from_db(select.getColumn(6).getInt64());
      if (!select.isColumnNull(7)) {
        e.mean_success_duration = Duration{static_cast<Duration::rep>(std::llround(select.getColumn(7).getDouble()))};
      }
      summary.attempts += e.attempts;
      summary.successes += e.successes;
      summary.edges.push_back(std::move(e));
    }
    return summary;
  });
}

}  // namespace rondo::store
