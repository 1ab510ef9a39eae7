// The first thing wrong with a task, a routine or a task set, as (field, message), so that the
// public validate() can prefix a path and the file decoders can add the file and line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rondo/core/routine.h"
#include "rondo/core/task.h"

namespace rondo::detail {

struct Problem {
  std::string field;    // relative to the thing checked, e.g. "window.deadline"
  std::string message;  // what is wrong
};

struct IndexedProblem {
  std::size_t index;  // which task of the set
  Problem problem;
};

std::optional<Problem> first_problem(const Task& task);
std::optional<IndexedProblem> first_problem(const std::vector<Task>& tasks);
std::optional<Problem> first_problem(const Routine& routine);
std::string join_path(const std::string& base, const std::string& field);

}  // namespace rondo::detail
