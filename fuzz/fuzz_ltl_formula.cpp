// libFuzzer target: task formulas (rondo::ltl::parse_formula). Any input gives a Formula or an
// error naming a position, never a crash or a hang; what it accepts prints to text that parses
// back to the same formula, and its automaton is built within the limits or refused.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "rondo/ltl/automaton.h"
#include "rondo/ltl/parser.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  const rondo::Result<rondo::ltl::Formula> f = rondo::ltl::parse_formula(text);
  if (!f) {
    if (!f.error().message.starts_with("position ") && !f.error().message.starts_with("the formula is ")) std::abort();
    return 0;
  }
  // Printing may lengthen the text ("a->b" is "!a | b"): read it back under wider limits.
  const rondo::Result<rondo::ltl::Formula> again =
      rondo::ltl::parse_formula(rondo::ltl::to_string(*f), {.max_bytes = 1 << 20, .max_depth = 1024});
  if (!again || !(*again == *f)) std::abort();
  (void)rondo::ltl::Automaton::build(*f, {.max_states = 64});
  return 0;
}
