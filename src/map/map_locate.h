// Private helper of the map loaders: turns a MapProblem into an error located at the line of the
// offending field in the source document.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "rondo/core/document.h"
#include "rondo/core/result.h"
#include "rondo/map/map_validation.h"

namespace rondo::map {

// An invalid-input error at `field_path` ("pose.position.x", "verts[2]", "" for the item itself)
// below `item`: that field's line when the document has it (a defaulted field has none), else the
// item's. `problem_count` > 1 adds "(and N more problems)".
Error locate_problem(const Field& item, std::string_view field_path, std::string_view message,
                     std::size_t problem_count);

// A name or id in single quotes for a message, cut at 60 characters, control characters shown as
// '?', so that a huge or binary name from a broken file cannot flood the output.
std::string quoted_name(const std::string& name);

// The same for a MapProblem whose `field` is a path in rondo's own format.
inline Error locate_problem(const Field& item, const MapProblem& problem, std::size_t problem_count) {
  return locate_problem(item, problem.field, problem.message, problem_count);
}

}  // namespace rondo::map
