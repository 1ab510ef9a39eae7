#include "rondo/plan/solution.h"

namespace rondo::plan {

const char* to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::kExact:
      return "exact";
    case SolveStatus::kConverged:
      return "converged";
    case SolveStatus::kSweepLimit:
      return "sweep-limit";
  }
  return "exact";
}

}  // namespace rondo::plan
