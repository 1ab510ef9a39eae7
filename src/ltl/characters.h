// The characters of node names and the reserved words, shared by the lexer and the printer.
#pragma once

#include <array>
#include <string_view>

namespace rondo::ltl {

inline bool is_name_start(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
inline bool is_name_char(char c) { return is_name_start(c) || (c >= '0' && c <= '9'); }

// Words that are operators or constants (or operators outside the fragment, refused by name); a
// node with such a name must be quoted.
inline constexpr std::array<std::string_view, 9> kReservedWords = {"X", "F", "U", "G", "R", "W", "M", "true", "false"};

}  // namespace rondo::ltl
