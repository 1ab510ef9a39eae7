#include "rondo/store/traversal_stats.h"

#include <cmath>

#include "store_access.h"

namespace rondo::store {

Result<TraversalSummary> summarize_traversals(const Store& store) {
  return guarded(store, "summarising traversals", [&]() -> Result<TraversalSummary> {
    auto select = connection(store).query(
        "SELECT edge_id, from_node, to_node, COUNT(*), SUM(success), MIN(start_ms), MAX(start_ms), "
        "AVG(CASE WHEN success = 1 THEN duration_ms END) "
        "FROM traversals GROUP BY edge_id, from_node, to_node ORDER BY edge_id, from_node, to_node");
    TraversalSummary summary;
    while (select->next()) {
      EdgeSummary e;
      e.edge_id = select->text(0);
      e.from = select->text(1);
      e.to = select->text(2);
      e.attempts = select->int64(3);
      e.successes = select->int64(4);
      e.first_start = time_from_db(select->int64(5));
      e.last_start = time_from_db(select->int64(6));
      if (!select->is_null(7)) {
        e.mean_success_duration = Duration{static_cast<Duration::rep>(std::llround(select->real(7)))};
      }
      summary.attempts += e.attempts;
      summary.successes += e.successes;
      summary.edges.push_back(std::move(e));
    }
    return summary;
  });
}

}  // namespace rondo::store
