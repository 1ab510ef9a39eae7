// The tasks that wait for a condition (MISSION.md §5, opportunistic tasks): a task whose door was
// seen closed is kept out of the schedule while its deadline allows, and waits for the door to be
// seen open. The executor decides (src/exec/executor_observations.cpp); this keeps the list.
//
//   opportunities.block("letter-drop", {.door = "A-120-door", .since = now, .seen_at = "Hall-A-120"});
//   for (const TaskId& id : opportunities.waiting_for("A-120-door")) ...
#pragma once

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/task.h"
#include "rondo/core/time.h"

namespace rondo::exec {

// What a blocked task waits for.
struct Blocked {
  std::string door;     // to be seen open
  Time since{};         // when it was seen closed
  std::string seen_at;  // the node the robot was at
  std::uint64_t serial = 0;  // set by block(): timers of an earlier block of the same task do nothing
};

class Opportunities {
 public:
  bool blocked(const TaskId& id) const { return find(id) != nullptr; }
  const Blocked* find(const TaskId& id) const {
    const auto it = std::find_if(list_.begin(), list_.end(), [&](const auto& e) { return e.first == id; });
    return it == list_.end() ? nullptr : &it->second;
  }
  // Returns the block's serial.
  std::uint64_t block(const TaskId& id, Blocked why) {
    if (const Blocked* b = find(id)) return b->serial;
    why.serial = ++serial_;
    list_.emplace_back(id, std::move(why));
    return serial_;
  }
  void unblock(const TaskId& id) {
    std::erase_if(list_, [&](const auto& e) { return e.first == id; });
  }
  // The tasks waiting for `door`, in the order they were blocked.
  std::vector<TaskId> waiting_for(const std::string& door) const {
    std::vector<TaskId> ids;
    for (const auto& [id, b] : list_)
      if (b.door == door) ids.push_back(id);
    return ids;
  }
  std::size_t size() const { return list_.size(); }

 private:
  std::vector<std::pair<TaskId, Blocked>> list_;
  std::uint64_t serial_ = 0;
};
}  // namespace rondo::exec
