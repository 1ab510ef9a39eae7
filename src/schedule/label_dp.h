// Label-setting dynamic program over partial sequences: a state is (set of tasks done, last task),
// a label on it is (end time, cost so far); a label is dominated by another on the same state that
// ends no later and costs no more (FIFO travel and waiting make the later one's completions
// reachable from the earlier one at no greater cost). Two modes:
// - exact (beam_width == 0): every non-dominated label is kept, pruned only by valid tests
//   (window elimination, cost + lower bound >= upper_bound); finishing proves the answer;
// - restricted (beam_width > 0): each stage keeps its best `beam_width` labels: a heuristic.
// Private to src/schedule.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "instance.h"
#include "rondo/schedule/stop_condition.h"

namespace rondo::schedule::detail {

struct LabelDpOptions {
  std::size_t beam_width = 0;                // 0 = exact
  std::size_t max_labels_per_stage = 2000000;  // exact mode gives up beyond this (~100 MB)
  std::size_t max_labels_total = 30000000;     // all stages (8 bytes each, for the answer's path)
  std::int64_t upper_bound = kNever;         // only sequences costing strictly less are sought
};

struct LabelDpResult {
  enum class Outcome {
    kFound,     // `order` is the best sequence found (optimal if `exhaustive`)
    kNoneFound, // nothing below the upper bound (proved if `exhaustive`)
    kAborted,   // stopped or over the label budget: nothing proved
  };
  Outcome outcome = Outcome::kAborted;
  bool exhaustive = false;  // exact mode ran to the end
  std::vector<std::size_t> order;
  std::int64_t objective = kNever;
  std::size_t labels = 0;  // created, for diagnostics
};

LabelDpResult run_label_dp(const Instance& instance, const LabelDpOptions& options, const StopCondition& stop);

}  // namespace rondo::schedule::detail
