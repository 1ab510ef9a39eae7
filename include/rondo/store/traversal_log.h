// The traversal log: every attempt to cross a map edge (rondo::Traversal), live from the executor
// or imported from old robot logs. The learners read it back by edge and by time. Append-only.
//
//   Result<bool> added = add_traversal(db, t);                  // false: its origin was already stored
//   Result<InsertCounts> n = add_traversals(db, many);          // all or nothing, one transaction
//   Result<std::vector<Traversal>> week = find_traversals(
//       db, {.edge_id = "Aisle1_Aisle2", .from = monday, .until = monday + hours(24 * 7)});
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/core/traversal.h"
#include "rondo/store/store.h"

namespace rondo::store {

// Stores one traversal in its own committed transaction. A traversal with an origin is stored at
// most once: adding it again changes nothing and returns false. One without (a live traversal) is
// always stored. Errors: kStorage.
Result<bool> add_traversal(Store& store, const Traversal& traversal);

struct InsertCounts {
  std::size_t inserted = 0;
  std::size_t already_present = 0;  // skipped because their origin was stored before

  bool operator==(const InsertCounts&) const = default;
};

struct BatchOptions {
  // Called on the calling thread as (rows_done, rows_total) after every `progress_every` rows,
  // while the transaction is still open: it must not use the store. Useful for a progress bar.
  std::function<void(std::size_t done, std::size_t total)> progress = {};
  std::size_t progress_every = 1000;
};

// Stores `traversals` in one transaction with one prepared statement: either all are committed or
// (on an error, or if the process dies first) none are. Like add_traversal, a traversal whose
// origin is already stored is skipped and counted in already_present. Errors: kStorage.
Result<InsertCounts> add_traversals(Store& store, std::span<const Traversal> traversals,
                                    const BatchOptions& options = {});

// Which traversals to read; every field that is set narrows the result.
struct TraversalQuery {
  std::optional<std::string> edge_id = std::nullopt;
  std::optional<Time> from = std::nullopt;   // start >= from
  std::optional<Time> until = std::nullopt;  // start < until
  std::optional<std::string> robot = std::nullopt;  // the robot that made it ('' : imported)
};

// The matching traversals ordered by start time, then edge, then insertion order. Queries by edge
// (with or without a time range) and by time range use indexes. Errors: kStorage.
Result<std::vector<Traversal>> find_traversals(const Store& store, const TraversalQuery& query = {});

// The number of stored traversals. Errors: kStorage.
Result<std::size_t> count_traversals(const Store& store);

}  // namespace rondo::store
