#include "rondo/ltl/task_formula.h"

#include <fmt/format.h>

#include "rondo/ltl/parser.h"

namespace rondo::ltl {

Result<std::shared_ptr<const Automaton>> task_automaton(std::string_view text, const KnownNode& known,
                                                        std::string_view map_name, const AutomatonOptions& options) {
  RONDO_ASSIGN_OR_RETURN(Formula formula, parse_formula(text));
  if (known) {
    for (const std::string& node : named_nodes(formula)) {
      if (!known(node))
        return Error::invalid(
            map_name.empty() ? fmt::format("the formula names '{}', which is not on the map", node)
                             : fmt::format("the formula names '{}', which is not on the map '{}'", node, map_name));
    }
  }
  RONDO_ASSIGN_OR_RETURN(Automaton automaton, Automaton::build(formula, options));
  return std::make_shared<const Automaton>(std::move(automaton));
}

Status check_task_formula(std::string_view text, const KnownNode& known, std::string_view map_name) {
  if (auto automaton = task_automaton(text, known, map_name); !automaton) return automaton.error();
  return {};
}

}  // namespace rondo::ltl
