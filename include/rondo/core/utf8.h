// UTF-8 well-formedness (no overlong forms, no surrogates, nothing above U+10FFFF). Document
// rejects text that fails it, and loaders of other formats use it so that every name they accept
// can be written to a file that Document reads back.
//
//   if (auto at = first_invalid_utf8(name)) return Error::invalid("byte " + std::to_string(*at) + "...");
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace rondo {

// The offset of the first byte that is not part of well-formed UTF-8, or nothing.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);

// `text` with every byte that is not part of well-formed UTF-8 replaced by '?'.
std::string replace_invalid_utf8(std::string_view text);

// `text` made safe to quote in a message: invalid UTF-8 and control characters become '?', and
// text longer than `max_chars` bytes is cut (at a character boundary) and ends in "...".
std::string quote_for_message(std::string_view text, std::size_t max_chars = 80);

// A path as text for a message: its bytes, with what is not UTF-8 replaced by '?'.
std::string printable_path(const std::filesystem::path& path);

}  // namespace rondo
