#include "lexer.h"

#include <algorithm>

#include <fmt/format.h>

#include "characters.h"
#include "rondo/core/utf8.h"

namespace rondo::ltl {

std::size_t character_position(std::string_view text, std::size_t offset) {
  std::size_t position = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i)
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++position;  // not a continuation byte
  return position;
}

Error syntax_error(std::string_view text, std::size_t offset, const std::string& what) {
  return Error::invalid(fmt::format("position {}: {}", character_position(text, offset), what));
}

namespace {

TokenKind word_kind(std::string_view word) {
  if (word == "X") return TokenKind::kNext;
  if (word == "F") return TokenKind::kEventually;
  if (word == "U") return TokenKind::kUntil;
  if (word == "true") return TokenKind::kTrue;
  if (word == "false") return TokenKind::kFalse;
  if (word == "G" || word == "R" || word == "W" || word == "M") return TokenKind::kOutside;
  return TokenKind::kName;
}

// A quoted name starting at text[start] == '"': its token, and the offset after the closing quote.
Result<Token> quoted_name(std::string_view text, std::size_t start, std::size_t& end) {
  std::string name;
  std::size_t i = start + 1;
  for (; i < text.size() && text[i] != '"'; ++i) {
    char c = text[i];
    if (c == '\\' && i + 1 < text.size() && (text[i + 1] == '"' || text[i + 1] == '\\')) c = text[++i];
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      return syntax_error(text, i, "a control character in a quoted node name");
    name += c;
  }
  if (i == text.size()) return syntax_error(text, start, "the quoted node name that starts here is not closed");
  if (name.empty()) return syntax_error(text, start, "an empty node name (\"\")");
  end = i + 1;
  return Token{TokenKind::kName, start, std::move(name)};
}

Result<Token> symbol(std::string_view text, std::size_t i, std::size_t& end) {
  end = i + 1;
  switch (text[i]) {
    case '!': return Token{TokenKind::kNot, i, "!"};
    case '&': return Token{TokenKind::kAnd, i, "&"};
    case '|': return Token{TokenKind::kOr, i, "|"};
    case '(': return Token{TokenKind::kOpen, i, "("};
    case ')': return Token{TokenKind::kClose, i, ")"};
    default: break;
  }
  const std::string_view rest = text.substr(i);
  if (rest.starts_with("->")) {
    end = i + 2;
    return Token{TokenKind::kImplies, i, "->"};
  }
  if (rest.starts_with("<->")) {
    end = i + 3;
    return Token{TokenKind::kOutside, i, "<->"};
  }
  const std::size_t width = std::min<std::size_t>(rest.size(), 4);  // at most one UTF-8 character
  std::size_t length = 1;
  while (length < width && (static_cast<unsigned char>(rest[length]) & 0xC0) == 0x80) ++length;
  return syntax_error(text, i, fmt::format("unexpected character '{}'", quote_for_message(rest.substr(0, length))));
}

}  // namespace

Result<std::vector<Token>> tokenize(std::string_view text) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      ++i;
    } else if (is_name_start(c)) {
      const std::size_t start = i;
      while (i < text.size() && is_name_char(text[i])) ++i;
      const std::string_view word = text.substr(start, i - start);
      tokens.push_back({word_kind(word), start, std::string(word)});
    } else if (c == '"') {
      std::size_t end = 0;
      RONDO_ASSIGN_OR_RETURN(Token t, quoted_name(text, i, end));
      tokens.push_back(std::move(t));
      i = end;
    } else {
      std::size_t end = 0;
      RONDO_ASSIGN_OR_RETURN(Token t, symbol(text, i, end));
      tokens.push_back(std::move(t));
      i = end;
    }
  }
  tokens.push_back({TokenKind::kEnd, text.size(), ""});
  return tokens;
}

}  // namespace rondo::ltl
