// The robot's last known state and the store's identity, kept so that an executive that restarts
// (after a crash, a reboot, an upgrade) comes back where it was: the robot at its last node with
// what it carries, and the run it belongs to.
//
//   save_robot_state(db, {.robot = "r1", .node = "WayPoint4", .battery = 0.8, .updated = now});
//   Result<std::optional<RobotState>> last = load_robot_state(db, "r1");   // nullopt: never saved
//   set_meta(db, "run.seed", "7");
//   Result<std::optional<std::string>> seed = get_meta(db, "run.seed");
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/time.h"
#include "rondo/store/store.h"

namespace rondo::store {

struct RobotState {
  std::string robot;
  std::string node;  // the last node the robot was known to be at
  std::optional<double> x{}, y{}, yaw{};
  std::optional<double> battery{};  // in [0, 1]
  Json on_board = Json::array();    // what it carries
  std::optional<std::string> fault{};
  Time updated{};

  bool operator==(const RobotState&) const = default;
};

// Replaces the robot's row, committed before it returns. Errors: kInvalidInput (no robot or node,
// a battery outside [0, 1], a pose that is not finite), kStorage.
Status save_robot_state(Store& store, const RobotState& state);
Result<std::optional<RobotState>> load_robot_state(const Store& store, std::string_view robot);

// The store's identity: small key/value facts (what run it holds). Errors: kStorage.
Status set_meta(Store& store, std::string_view key, std::string_view value);
Result<std::optional<std::string>> get_meta(const Store& store, std::string_view key);
// Sets `key` to `value` unless it is set already, in one statement: nothing when it was set by
// this call, else the value it holds (left as it is).
Result<std::optional<std::string>> claim_meta(Store& store, std::string_view key, std::string_view value);
// Sets several keys in one transaction: all of them or, on an error or a crash, none.
Status set_meta(Store& store, const std::vector<std::pair<std::string, std::string>>& entries);
// Every key and its value.
Result<std::map<std::string, std::string>> read_meta(const Store& store);

}  // namespace rondo::store
