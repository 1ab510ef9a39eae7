#include "rondo/exec/robot.h"

namespace rondo::exec {

const char* to_string(ActionOutcome outcome) {
  switch (outcome) {
    case ActionOutcome::kSucceeded: return "succeeded";
    case ActionOutcome::kFailed: return "failed";
    case ActionOutcome::kCancelled: return "cancelled";
  }
  return "unknown";
}

}  // namespace rondo::exec
