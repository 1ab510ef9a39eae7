#include "rondo/core/task.h"

#include <functional>
#include <set>
#include <unordered_map>

#include "task_problem.h"

namespace rondo {

bool is_final(TaskState s) {
  switch (s) {
    case TaskState::kSucceeded:
    case TaskState::kFailed:
    case TaskState::kCancelled:
    case TaskState::kPreempted:
    case TaskState::kDropped:
      return true;
    default:
      return false;
  }
}

const char* to_string(TaskKind k) { return k == TaskKind::kStandard ? "standard" : "on-demand"; }
const char* to_string(DeliveryRole r) { return r == DeliveryRole::kPickup ? "pickup" : "drop"; }

const char* to_string(TaskState s) {
  switch (s) {
    case TaskState::kQueued: return "queued";
    case TaskState::kWaiting: return "waiting";
    case TaskState::kNavigating: return "navigating";
    case TaskState::kActing: return "acting";
    case TaskState::kSucceeded: return "succeeded";
    case TaskState::kFailed: return "failed";
    case TaskState::kCancelled: return "cancelled";
    case TaskState::kPreempted: return "preempted";
    case TaskState::kDropped: return "dropped";
  }
  return "unknown";
}

Result<TaskKind> parse_task_kind(std::string_view text) {
  if (text == "standard") return TaskKind::kStandard;
  if (text == "on-demand" || text == "on_demand") return TaskKind::kOnDemand;
  return Error::invalid("unknown task kind '" + std::string(text) + "' (expected standard or on-demand)");
}

Result<DeliveryRole> parse_delivery_role(std::string_view text) {
  if (text == "pickup") return DeliveryRole::kPickup;
  if (text == "drop") return DeliveryRole::kDrop;
  return Error::invalid("unknown delivery role '" + std::string(text) + "' (expected pickup or drop)");
}

Result<TaskState> parse_task_state(std::string_view text) {
  for (auto s : {TaskState::kQueued, TaskState::kWaiting, TaskState::kNavigating, TaskState::kActing,
                 TaskState::kSucceeded, TaskState::kFailed, TaskState::kCancelled, TaskState::kPreempted,
                 TaskState::kDropped}) {
    if (text == to_string(s)) return s;
  }
  return Error::invalid("unknown task state '" + std::string(text) + "'");
}

namespace detail {

std::optional<Problem> first_problem(const Task& t) {
  if (t.id.empty()) return Problem{"id", "a task needs a non-empty id"};
  if (t.kind == TaskKind::kStandard && !t.window) {
    return Problem{"window", "a standard task needs a time window {release, deadline}"};
  }
  if (t.kind == TaskKind::kOnDemand && t.window) {
    return Problem{"window", "an on-demand task runs now and has no time window"};
  }
  if (t.duration < Duration{0}) return Problem{"duration", "must not be negative"};
  if (t.window) {
    if (t.window->deadline < t.window->release) {
      return Problem{"window.deadline", "deadline " + format_time(t.window->deadline) + " is before the release " +
                                            format_time(t.window->release)};
    }
    if (t.duration > t.window->width()) {
      return Problem{"duration", "duration " + format_duration(t.duration) + " is longer than the window (" +
                                     format_duration(t.window->width()) + ")"};
    }
  }
  if (t.has_spec()) {
    if (!t.start_node.empty()) return Problem{"spec", "a task has a spec or a start_node, not both"};
    if (!t.end_node.empty())
      return Problem{"end_node", "a spec task ends where its formula is satisfied: it takes no end_node"};
    if (t.delivery) return Problem{"delivery", "a delivery picks up and drops at a start_node: it takes no spec"};
  }
  if (t.start_node.empty() && !t.end_node.empty()) {
    return Problem{"end_node", "an end node needs a start node"};
  }
  for (std::size_t i = 0; i < t.actions.size(); ++i) {
    if (t.actions[i].name.empty()) {
      return Problem{"actions[" + std::to_string(i) + "].name", "an action needs a name"};
    }
  }
  if (t.delivery) {
    if (t.delivery->job.empty()) return Problem{"delivery.job", "a delivery needs a job id"};
    if (t.delivery->object.empty()) return Problem{"delivery.object", "a delivery needs an object"};
    if (t.delivery->load < 1) return Problem{"delivery.load", "load must be at least 1"};
    if (t.start_node.empty()) return Problem{"start_node", "a delivery needs a place to pick up or drop at"};
  }
  std::set<TaskId> seen;
  for (std::size_t i = 0; i < t.after.size(); ++i) {
    if (t.after[i] == t.id) return Problem{"after[" + std::to_string(i) + "]", "a task cannot come after itself"};
    if (!seen.insert(t.after[i]).second) {
      return Problem{"after[" + std::to_string(i) + "]", "'" + t.after[i] + "' is listed twice"};
    }
  }
  return std::nullopt;
}

std::optional<IndexedProblem> first_problem(const std::vector<Task>& tasks) {
  std::unordered_map<TaskId, std::size_t> index;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (!index.emplace(tasks[i].id, i).second) {
      return IndexedProblem{i, {"id", "duplicate task id '" + tasks[i].id + "'"}};
    }
  }
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    for (std::size_t k = 0; k < tasks[i].after.size(); ++k) {
      if (!index.count(tasks[i].after[k])) {
        return IndexedProblem{i, {"after[" + std::to_string(k) + "]", "no task '" + tasks[i].after[k] + "'"}};
      }
    }
  }
  // Precedence cycles: depth-first search with three colours.
  std::vector<int> colour(tasks.size(), 0);
  std::optional<IndexedProblem> cycle;
  std::function<bool(std::size_t)> visit = [&](std::size_t i) {
    colour[i] = 1;
    for (const auto& before : tasks[i].after) {
      const std::size_t j = index.at(before);
      if (colour[j] == 1) {
        cycle = IndexedProblem{i, {"after", "precedence cycle through '" + tasks[i].id + "' and '" + before + "'"}};
        return false;
      }
      if (colour[j] == 0 && !visit(j)) return false;
    }
    colour[i] = 2;
    return true;
  };
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (colour[i] == 0 && !visit(i)) return cycle;
  }
  // Delivery jobs: one pickup and one drop of the same object.
  struct Halves {
    std::optional<std::size_t> pickup, drop;
  };
  std::map<std::string, Halves> jobs;
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (!tasks[i].delivery) continue;
    auto& h = jobs[tasks[i].delivery->job];
    auto& slot = tasks[i].delivery->role == DeliveryRole::kPickup ? h.pickup : h.drop;
    if (slot) {
      return IndexedProblem{i, {"delivery.role", "job '" + tasks[i].delivery->job + "' already has a " +
                                                     to_string(tasks[i].delivery->role) + " task ('" +
                                                     tasks[*slot].id + "')"}};
    }
    slot = i;
  }
  for (const auto& [job, h] : jobs) {
    if (!h.pickup || !h.drop) {
      const std::size_t i = h.pickup ? *h.pickup : *h.drop;
      return IndexedProblem{i, {"delivery", std::string("job '") + job + "' has no " + (h.pickup ? "drop" : "pickup") + " task"}};
    }
    const auto& a = *tasks[*h.pickup].delivery;
    const auto& b = *tasks[*h.drop].delivery;
    if (a.object != b.object || a.appearance != b.appearance || a.load != b.load) {
      return IndexedProblem{*h.drop, {"delivery", "job '" + job + "': the drop names another object than the pickup"}};
    }
  }
  return std::nullopt;
}

std::string join_path(const std::string& base, const std::string& field) {
  if (base.empty()) return field;
  if (field.empty()) return base;
  return base + "." + field;
}

}  // namespace detail

Status validate(const Task& task, const std::string& path) {
  if (auto p = detail::first_problem(task)) {
    return Error::invalid(detail::join_path(path, p->field) + ": " + p->message);
  }
  return {};
}

Status validate(const std::vector<Task>& tasks, const std::string& path) {
  for (std::size_t i = 0; i < tasks.size(); ++i) {
    if (auto s = validate(tasks[i], path + "[" + std::to_string(i) + "]"); !s) return s;
  }
  if (auto p = detail::first_problem(tasks)) {
    return Error::invalid(detail::join_path(path + "[" + std::to_string(p->index) + "]", p->problem.field) + ": " +
                          p->problem.message);
  }
  return {};
}

}  // namespace rondo
