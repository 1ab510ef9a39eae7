#include "rondo/vda5050/messages.h"

namespace rondo::vda5050 {

const char* to_string(BlockingType t) {
  switch (t) {
    case BlockingType::kNone:
      return "NONE";
    case BlockingType::kSoft:
      return "SOFT";
    case BlockingType::kHard:
      return "HARD";
  }
  return "?";
}

const char* to_string(ActionStatus s) {
  switch (s) {
    case ActionStatus::kWaiting:
      return "WAITING";
    case ActionStatus::kInitializing:
      return "INITIALIZING";
    case ActionStatus::kRunning:
      return "RUNNING";
    case ActionStatus::kPaused:
      return "PAUSED";
    case ActionStatus::kFinished:
      return "FINISHED";
    case ActionStatus::kFailed:
      return "FAILED";
  }
  return "?";
}

const char* to_string(ErrorLevel l) {
  return l == ErrorLevel::kFatal ? "FATAL" : "WARNING";
}

const char* to_string(OperatingMode m) {
  switch (m) {
    case OperatingMode::kAutomatic:
      return "AUTOMATIC";
    case OperatingMode::kSemiautomatic:
      return "SEMIAUTOMATIC";
    case OperatingMode::kManual:
      return "MANUAL";
    case OperatingMode::kService:
      return "SERVICE";
    case OperatingMode::kTeachin:
      return "TEACHIN";
  }
  return "?";
}

const char* to_string(ConnectionState c) {
  switch (c) {
    case ConnectionState::kOnline:
      return "ONLINE";
    case ConnectionState::kOffline:
      return "OFFLINE";
    case ConnectionState::kConnectionBroken:
      return "CONNECTIONBROKEN";
  }
  return "?";
}

}  // namespace rondo::vda5050
