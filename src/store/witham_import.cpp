#include "rondo/store/witham_import.h"

#include <algorithm>
#include <set>
#include <string>

#include "rondo/core/traversal.h"

namespace rondo::store {

Result<WithamImport> import_witham_logs(Store& store, const std::filesystem::path& dir, const BatchOptions& options) {
  auto records = read_witham_logs(dir);
  if (!records) return records.error();
  WithamImport report;
  report.attempts = records->size();
  report.successes = static_cast<std::size_t>(
      std::count_if(records->begin(), records->end(), [](const Traversal& t) { return t.success; }));
  std::set<std::string> edges;
  for (const Traversal& t : *records) edges.insert(t.edge_id);
  report.edges = edges.size();
  auto stored = add_traversals(store, *records, options);
  if (!stored) return stored.error();
  report.stored = *stored;
  return report;
}

}  // namespace rondo::store
