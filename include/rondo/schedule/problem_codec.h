// Our problem format (JSON or YAML, documented in docs/scheduling.md) and the JSON form of a
// schedule.
//
//   Result<Problem> p = load_problem("day.yaml");
//   // error: "day.yaml:14: tasks[2].start: no location 'B' in locations"
//   Json out = schedule_to_json(*p, schedule);
#pragma once

#include <filesystem>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/schedule/problem.h"
#include "rondo/schedule/schedule.h"

namespace rondo::schedule {

Result<Problem> decode_problem(const Document& document);
Result<Problem> load_problem(const std::filesystem::path& file);

// {"status", "objective" (seconds), "order" (task ids), "seconds", "entries": [...], "dropped"}.
Json schedule_to_json(const Problem& problem, const Schedule& schedule);

}  // namespace rondo::schedule
