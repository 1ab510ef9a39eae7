// One attempt to cross a map edge: the experience that the learned navigation models are fitted
// from. Recorded by the executor, stored by rondo::store, and imported from real robot logs.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo {

struct Traversal {
  std::string edge_id{};  // the map's edge id; "<from>_<to>" in the Witham Wharf logs
  std::string from{};     // node the attempt started at
  std::string to{};       // node it was meant to reach
  Time start{};
  Duration duration{};
  bool success = false;
  // Where the record came from, unique per record: "witham:Aisle1_Aisle2.data:17" for an imported
  // log line; empty for a traversal the robot just made.
  std::string origin{};
  // The robot that made the attempt (a fleet's robots feed one log); empty when not known, as in
  // an imported log.
  std::string robot{};
  // How long the robot waited, before the attempt, for other robots to free the way (the traffic
  // manager's reservations, docs/traffic.md): the fleet's own traffic, kept apart from `duration`,
  // the building's, which the models learn from.
  Duration waited{0};

  bool operator==(const Traversal&) const = default;
};

// Reads one Witham Wharf edge log, "<From>_<To>.data", one `unix_time duration_s success` line per
// attempt. A malformed line is an error naming the file and the line.
Result<std::vector<Traversal>> read_witham_edge_log(const std::filesystem::path& file);

// Reads every "*.data" file of a Witham Wharf folder; attempts sorted by start time, then edge.
Result<std::vector<Traversal>> read_witham_logs(const std::filesystem::path& dir);

}  // namespace rondo
