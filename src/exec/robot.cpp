#include "rondo/exec/robot.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

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

std::optional<std::string> cannot_run(const Robot& robot, const std::vector<Action>& actions) {
  const std::optional<ActionSupport> support = robot.supported_actions();
  if (!support || support->actions.empty()) return std::nullopt;
  for (const Action& a : actions) {
    if (std::find(support->actions.begin(), support->actions.end(), a.name) != support->actions.end()) continue;
    return fmt::format("{} cannot run the action '{}'; it runs: {}", support->robot, a.name,
                       fmt::join(support->actions, ", "));
  }
  return std::nullopt;
}

}  // namespace rondo::exec
