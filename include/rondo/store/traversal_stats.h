// Per-edge summaries of the traversal log, computed by the database: what `rondo log stats` shows
// and a quick check of what the learners have to work with.
//
//   Result<TraversalSummary> s = summarize_traversals(db);
//   for (const EdgeSummary& e : s->edges) std::cout << e.edge_id << ' ' << e.attempts << '\n';
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct EdgeSummary {
  std::string edge_id;
  std::string from;
  std::string to;
  std::int64_t attempts = 0;
  std::int64_t successes = 0;
  Time first_start;  // earliest attempt
  Time last_start;   // latest attempt
  // Mean duration of the successful attempts; empty when there were none.
  std::optional<Duration> mean_success_duration;
};

struct TraversalSummary {
  std::int64_t attempts = 0;
  std::int64_t successes = 0;
  std::vector<EdgeSummary> edges;  // ordered by edge id
};

// Errors: kStorage.
Result<TraversalSummary> summarize_traversals(const Store& store);

}  // namespace rondo::store
