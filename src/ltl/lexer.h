// The tokens of a formula (docs/ltl.md, "Grammar"), with their byte offsets for error messages.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "rondo/core/result.h"

namespace rondo::ltl {

enum class TokenKind {
  kName,  // a node: bare or quoted; Token::text is the name without quotes or escapes
  kTrue,
  kFalse,
  kNot,         // !
  kAnd,         // &
  kOr,          // |
  kNext,        // X
  kEventually,  // F
  kUntil,       // U
  kImplies,     // ->
  kOpen,        // (
  kClose,       // )
  kOutside,     // an operator outside the fragment: G, R, W, M, <->; Token::text is its spelling
  kEnd,
};

struct Token {
  TokenKind kind;
  std::size_t offset;  // of the token's first byte
  std::string text;
};

// The tokens of `text`, ending with kEnd; an error ("position N: ...") for a character that
// starts no token, a quoted name that is empty, not closed, or holds a control character.
// Precondition: `text` is valid UTF-8.
Result<std::vector<Token>> tokenize(std::string_view text);

// The 1-based position, in characters (UTF-8 code points), of the byte at `offset`.
std::size_t character_position(std::string_view text, std::size_t offset);

// "position N: what" for the byte at `offset` of `text`.
Error syntax_error(std::string_view text, std::size_t offset, const std::string& what);

}  // namespace rondo::ltl
