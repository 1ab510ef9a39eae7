// Loads the Witham Wharf edge logs (one "<From>_<To>.data" file per edge) into the traversal log.
// The import is atomic and idempotent: one transaction, and each log line's origin
// ("witham:<file>:<line>") is stored at most once, so an interrupted import leaves nothing behind
// and running it again adds only what is missing.
//
//   Result<WithamImport> r = import_witham_logs(db, "../shared/data/witham_wharf");
//   // r->attempts == 32078, r->inserted + r->already_present == r->attempts
#pragma once

#include <cstddef>
#include <filesystem>

#include "rondo/core/result.h"
#include "rondo/store/store.h"
#include "rondo/store/traversal_log.h"

namespace rondo::store {

struct WithamImport {
  std::size_t attempts = 0;   // traversal records read from the logs
  std::size_t successes = 0;  // of which successful
  std::size_t edges = 0;      // distinct edges among them
  InsertCounts stored;        // inserted now vs already in the store
};

// Reads every edge log of `dir` (rondo::read_witham_logs) and stores them with add_traversals;
// `options.progress` sees the rows as they are inserted. Nothing is written unless every file
// parses. Errors: kNotFound (no such folder), kInvalidInput (a malformed log, naming file and
// line), kStorage.
Result<WithamImport> import_witham_logs(Store& store, const std::filesystem::path& dir,
                                        const BatchOptions& options = {});

}  // namespace rondo::store
