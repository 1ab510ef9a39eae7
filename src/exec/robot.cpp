#include "rondo/exec/robot.h"

namespace rondo::exec {

const char* to_string(EdgeOutcome outcome) {
  switch (outcome) {
    case EdgeOutcome::kSucceeded: return "succeeded";
    case EdgeOutcome::kFailed: return "failed";
    case EdgeOutcome::kCancelled: return "cancelled";
    case EdgeOutcome::kRobotFault: return "robot fault";
  }
  return "unknown";
}

const char* to_string(ActionOutcome outcome) {
  switch (outcome) {
    case ActionOutcome::kSucceeded: return "succeeded";
    case ActionOutcome::kFailed: return "failed";
    case ActionOutcome::kCancelled: return "cancelled";
    case ActionOutcome::kRobotFault: return "robot fault";
  }
  return "unknown";
}

const char* to_string(RobotFault::Kind kind) {
  switch (kind) {
    case RobotFault::Kind::kError: return "error";
    case RobotFault::Kind::kConnectionLost: return "connection lost";
  }
  return "unknown";
}

}  // namespace rondo::exec
