// The task: rondo's unit of behaviour (MISSION.md §1). A task has a place, a time window, an
// expected duration, a priority and an activity made of indivisible actions.
//
//   Task t;
//   t.id = "fire-door-3";
//   t.activity = "check the fire door";
//   t.window = TimeWindow{release, deadline};   // the task must start at or after release
//   t.duration = minutes(2);                    // and end at or before deadline
//   t.start_node = "WayPoint3";
//   t.actions = {Action{"check_door", {{"door", "fd3"}}}};
//   if (auto ok = validate(t); !ok) std::cerr << ok.error().message;
//
// Tasks are values; the executor owns their run-time state (TaskState) separately.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rondo/core/result.h"
#include "rondo/core/time.h"

namespace rondo {

using TaskId = std::string;

enum class TaskKind {
  kStandard,  // scheduled inside its time window
  kOnDemand,  // no window: runs now, preempting an interruptible running task
};

// <r, d>: the release r is the earliest start and the deadline d the latest end.
struct TimeWindow {
  Time release;
  Time deadline;
  Duration width() const { return deadline - release; }
  bool operator==(const TimeWindow&) const = default;
};

// One indivisible step of an activity, e.g. {"say", {{"text", "hello"}}}.
struct Action {
  std::string name;
  std::map<std::string, std::string> args;
  bool operator==(const Action&) const = default;
};

enum class DeliveryRole { kPickup, kDrop };

// The half of a delivery job that a task performs (MISSION.md §5): the pickup task loads the
// object, the drop task unloads it. Both tasks of a job name the same job and object.
struct Delivery {
  std::string job;         // the delivery job both halves belong to
  DeliveryRole role = DeliveryRole::kPickup;
  std::string object;      // what is carried, e.g. "green book"
  std::string appearance;  // what it looks like; two objects that look the same are never on board together
  int load = 1;            // capacity units the object takes on board
  bool operator==(const Delivery&) const = default;
};

struct Task {
  TaskId id;
  std::string activity;  // what it is for, e.g. "check the fire extinguisher"
  TaskKind kind = TaskKind::kStandard;
  std::optional<TimeWindow> window;  // required for standard tasks, absent for on-demand ones
  Duration duration{0};              // expected processing time p
  int priority = 0;                  // higher is more important
  std::string start_node;            // empty: the task has no place (it runs where the robot is)
  std::string end_node;              // empty: ends where it starts
  // A co-safe LTL formula over the map's nodes (docs/ltl.md), instead of start_node: the task's
  // journey is the way that satisfies it, and its actions run where it is satisfied. Empty: none.
  std::string spec;
  std::vector<Action> actions;
  bool interruptible = true;         // initial value; the running task may change it
  std::optional<Delivery> delivery;
  std::vector<TaskId> after;         // tasks that must end before this one starts
  std::string robot;                 // the robot that must do it (a fleet's name); empty: any robot

  // Where the robot is when the task ends (empty for a spec task: where its formula is satisfied).
  const std::string& end_location() const { return end_node.empty() ? start_node : end_node; }
  bool has_spec() const { return !spec.empty(); }
  bool operator==(const Task&) const = default;
};

// Where a task is in its life (DESIGN.md, Executor). The last five are final.
enum class TaskState {
  kQueued,
  kWaiting,
  kNavigating,
  kActing,
  kSucceeded,
  kFailed,
  kCancelled,
  kPreempted,
  kDropped,
};

bool is_final(TaskState s);

const char* to_string(TaskKind k);
const char* to_string(DeliveryRole r);
const char* to_string(TaskState s);
Result<TaskKind> parse_task_kind(std::string_view text);
Result<DeliveryRole> parse_delivery_role(std::string_view text);
Result<TaskState> parse_task_state(std::string_view text);

// Checks one task for what cannot be meant: no id, a standard task without a window or an
// on-demand one with a window, a deadline before the release, a duration longer than the window,
// an end node without a start node, an empty action name, a delivery without a job or with a
// load below 1, a spec beside a start node, an end node or a delivery. The message names the
// field, prefixed by `path` (e.g. "tasks[3]").
Status validate(const Task& task, const std::string& path = "");

// Checks a set of tasks together: unique ids, `after` naming existing tasks and no cycle, each
// delivery job with exactly one pickup and one drop, at one object.
Status validate(const std::vector<Task>& tasks, const std::string& path = "tasks");

}  // namespace rondo
