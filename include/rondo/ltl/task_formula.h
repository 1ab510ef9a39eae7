// A task's `spec:` (docs/task-format.md): the formula read and its automaton built under the
// limits, and the nodes it names checked against a map, in one call for every place a task comes
// in (task files, deployments, the API, commands in words).
//
//   Result<std::shared_ptr<const Automaton>> a = task_automaton("F A & !D U B", known_on_map);
//   // refused: "position 1: 'G' (always) is outside the co-safe fragment: ..."
//   //          "the formula names 'Lab', which is not on the map 'g4s'"
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "rondo/core/result.h"
#include "rondo/ltl/automaton.h"

namespace rondo::ltl {

using KnownNode = std::function<bool(std::string_view)>;

// The automaton of `text`, or kInvalidInput: the parser's refusal (with its position), the
// automaton's limit passed, or (when `known` is set) the first named node it does not know.
Result<std::shared_ptr<const Automaton>> task_automaton(std::string_view text, const KnownNode& known = {},
                                                        std::string_view map_name = "",
                                                        const AutomatonOptions& options = {});

// The same, without the automaton: for core's PlaceCheck::spec.
Status check_task_formula(std::string_view text, const KnownNode& known = {}, std::string_view map_name = "");

}  // namespace rondo::ltl
