// Private helper of rondo::map: UTF-8 well-formedness, with the same rules as rondo::Document
// (no overlong forms, no surrogates, nothing above U+10FFFF), so that every name a map holds can
// be written to a file that Document reads back.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace rondo::map {

// The offset of the first byte that is not part of well-formed UTF-8, or nothing.
std::optional<std::size_t> first_invalid_utf8(std::string_view text);

// `text` with every byte that is not part of well-formed UTF-8 replaced by '?'.
std::string replace_invalid_utf8(std::string_view text);

}  // namespace rondo::map
