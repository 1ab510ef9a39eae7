// Reading and writing tasks and routines as YAML or JSON (the format is docs/task-format.md).
//
//   Result<TaskFile> file = load_task_file("day.yaml");
//   if (!file) { std::cerr << file.error().message; return 2; }   // "day.yaml:7: tasks[1].window..."
//   for (const Task& t : file->tasks) ...
//   std::string yaml = to_yaml(encode(*file));
//
// Decoding validates: every value that reaches the caller passes validate().
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/core/routine.h"
#include "rondo/core/task.h"
#include "rondo/core/timezone.h"

namespace rondo {

// A file of tasks and routines, with the time zone its local times and routines are read in.
struct TaskFile {
  std::optional<TimeZone> zone;  // required when the file has routines or local times
  std::vector<Task> tasks;
  std::vector<Routine> routines;
};

// The places a file may name, when the map is known (a deployment): a start_node or end_node that
// `known` refuses is an error at its field ("routines.yaml:12: routines[0].task.start_node: node
// 'Lab' is not on the map 'g4s'"). Without one, node names are not checked. A task's `spec:`
// (a formula: core cannot read it) is checked by `spec` when set (ltl::check_task_formula: the
// fragment, the automaton's size, the nodes), its error shown at the field; `known` may then be
// empty, for a check without a map.
struct PlaceCheck {
  std::function<bool(std::string_view)> known;
  std::string map_name;
  std::function<Status(std::string_view formula)> spec{};
};

// Times without an explicit zone are read in `zone`; with no zone they are an error.
Result<Task> decode_task(const Field& field, const TimeZone* zone, const PlaceCheck* places = nullptr);
Result<Routine> decode_routine(const Field& field, const PlaceCheck* places = nullptr);
// An action: a name, or {name, args: {key: text | number | bool}}.
Result<Action> decode_action(const Field& field);
// Besides each task and routine: task ids are unique, routine names are unique, and no task id
// has the form of a routine's instance ids ("<routine name>@...").
Result<TaskFile> decode_task_file(const Document& doc, const PlaceCheck* places = nullptr);
Result<TaskFile> load_task_file(const std::filesystem::path& file, const PlaceCheck* places = nullptr);
Result<TaskFile> parse_task_file(std::string_view text, DocumentFormat format, std::string source,
                                 const PlaceCheck* places = nullptr);

// Times are written in UTC ("...Z"), durations in their human form ("1h30m"); fields that hold
// their default value are left out, so decode(encode(x)) == x.
Json encode(const Task& task);
Json encode(const Routine& routine);
Json encode(const TaskFile& file);

}  // namespace rondo
